#include "solver/kept_rays.h"

#include <algorithm>
#include <cassert>

#include "solver/solver_state.h"

namespace rad {

KeptRays* prepare_kept_rays(SolverState& s, const ShotSource& src) {
  if (s.cluster_last_shot.size() != s.clusters.size()) {
    s.cluster_last_shot.assign(s.clusters.size(), 0);
  }
  // This shot's number (1-based: s.shots counts the shots done before it).
  const uint64_t shot = uint64_t(s.shots) + 1;
  uint64_t& last = s.cluster_last_shot[size_t(src.cluster)];
  const bool again_soon = last != 0 && shot - last <= kKeptWithin;
  last = shot;
  auto found = s.kept_rays.find(src.cluster);
  if (s.options.kept_rays_bytes == 0 || src.sample_count == 0) return nullptr;
  if (!again_soon && found == s.kept_rays.end()) return nullptr;

  const uint32_t words = uint32_t((src.sample_count + 63) / 64);
  size_t wanted = s.receivers.size() * (sizeof(uint32_t) + sizeof(std::vector<uint64_t>)) +
                  src.sample_count * (sizeof(uint32_t) + 3 * sizeof(float));
  for (uint32_t p : s.receivers) {
    wanted += s.mesh.polygons[p].vertex_count() * (1 + words) * sizeof(uint64_t);
  }
  const auto fits = [&] {
    const size_t held = found == s.kept_rays.end() ? 0 : found->second.bytes;
    return s.kept_rays_bytes - held + wanted <= s.options.kept_rays_bytes;
  };
  if (!fits()) {
    // Make room from the clusters that have not shot for a while: they may never again.
    for (auto it = s.kept_rays.begin(); it != s.kept_rays.end();) {
      if (it->first != src.cluster && shot - s.cluster_last_shot[size_t(it->first)] > kKeptWithin) {
        s.kept_rays_bytes -= it->second.bytes;
        it = s.kept_rays.erase(it);
      } else {
        ++it;
      }
    }
    found = s.kept_rays.find(src.cluster);
    if (!fits()) {
      // This cluster's answers have outgrown the memory left (its receivers subdivide): they
      // would never fit again.
      if (found != s.kept_rays.end()) {
        s.kept_rays_bytes -= found->second.bytes;
        s.kept_rays.erase(found);
      }
      return nullptr;
    }
  }
  KeptRays& k = found == s.kept_rays.end() ? s.kept_rays[src.cluster] : found->second;
  // The samples are geometry too, but the answers are only good for the same samples.
  if (k.words != words || k.moved.size() != src.sample_count) {
    s.kept_rays_bytes -= k.bytes;
    k = KeptRays{};
    k.words = words;
    k.moved.assign(src.sample_count, 0);
    k.end_x.assign(src.sample_count, 0.0f);
    k.end_y = k.end_x, k.end_z = k.end_x;
  }
  if (k.receivers != s.receivers) {
    // Another list (the roulette's draw, a subdivided neighbour, an edit): the polygons on both
    // keep their answers (a vertex's rays are the same segments), the others start untraced.
    // Both lists are in index order.
    assert(std::is_sorted(s.receivers.begin(), s.receivers.end()));
    std::vector<std::vector<uint64_t>> answers(s.receivers.size());
    size_t j = 0;
    for (size_t i = 0; i < s.receivers.size(); ++i) {
      while (j < k.receivers.size() && k.receivers[j] < s.receivers[i]) ++j;
      if (j < k.receivers.size() && k.receivers[j] == s.receivers[i]) {
        answers[i] = std::move(k.answers[j]);
      }
    }
    k.answers = std::move(answers);
    k.receivers = std::vector<uint32_t>(s.receivers);  // a fresh copy: no capacity left uncounted
  }
  ++k.epoch;
  for (size_t g = 0; g < src.sample_count; ++g) {
    if (k.epoch == 1 || src.end_x[g] != k.end_x[g] || src.end_y[g] != k.end_y[g] ||
        src.end_z[g] != k.end_z[g]) {
      k.moved[g] = k.epoch;
      k.end_x[g] = src.end_x[g], k.end_y[g] = src.end_y[g], k.end_z[g] = src.end_z[g];
    }
  }
  k.answers.resize(s.receivers.size());
  for (size_t i = 0; i < s.receivers.size(); ++i) {
    // Vertices made since the last shot start at epoch 0: never traced. Reserved exactly (a
    // vector's growth would hold up to twice as much), so `wanted` is what is held.
    const size_t n = s.mesh.polygons[s.receivers[i]].vertex_count() * (1 + words);
    k.answers[i].reserve(n);
    k.answers[i].resize(n, 0);
  }
  s.kept_rays_bytes = s.kept_rays_bytes - k.bytes + wanted;
  k.bytes = wanted;
  return &k;
}

}  // namespace rad
