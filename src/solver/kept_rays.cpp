#include "solver/kept_rays.h"

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
  if (s.options.kept_rays_bytes == 0 || src.sample_count == 0) return nullptr;
  if (!again_soon && !s.kept_rays.contains(src.cluster)) return nullptr;
  const uint32_t words = uint32_t((src.sample_count + 63) / 64);
  size_t wanted = s.receivers.size() * (sizeof(uint32_t) + sizeof(std::vector<uint64_t>));
  for (uint32_t p : s.receivers) {
    wanted += s.mesh.polygons[p].vertex_count() * (1 + words) * sizeof(uint64_t);
  }
  const auto found = s.kept_rays.find(src.cluster);
  const size_t held = found == s.kept_rays.end() ? 0 : found->second.bytes;
  if (s.kept_rays_bytes - held + wanted > s.options.kept_rays_bytes) return nullptr;
  KeptRays& k = found == s.kept_rays.end() ? s.kept_rays[src.cluster] : found->second;
  // The receivers are geometry too, but the answers are only good for the same list.
  if (k.words != words || k.receivers != s.receivers) {
    k = KeptRays{};
    k.words = words;
    k.receivers = s.receivers;
    k.moved.assign(src.sample_count, 0);
    k.end_x.assign(src.sample_count, 0.0f);
    k.end_y = k.end_x, k.end_z = k.end_x;
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
    // Vertices made since the last shot start at epoch 0: never traced.
    k.answers[i].resize(s.mesh.polygons[s.receivers[i]].vertex_count() * (1 + words), 0);
  }
  s.kept_rays_bytes = s.kept_rays_bytes - held + wanted;
  k.bytes = wanted;
  return &k;
}

}  // namespace rad
