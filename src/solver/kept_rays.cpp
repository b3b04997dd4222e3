#include "solver/kept_rays.h"

#include <algorithm>
#include <cassert>

namespace rad {

KeptRays* prepare_kept_rays(KeptRayStore& store, const ShotSource& src, uint64_t shot,
                            std::span<const uint32_t> receivers, const Mesh& mesh,
                            size_t cluster_count, size_t max_bytes) {
  if (store.last_shot.size() != cluster_count) store.last_shot.assign(cluster_count, 0);
  uint64_t& last = store.last_shot[size_t(src.cluster)];
  const bool again_soon = last != 0 && shot - last <= kKeptWithin;
  last = shot;
  auto found = store.clusters.find(src.cluster);
  if (max_bytes == 0 || src.sample_count == 0) return nullptr;
  if (!again_soon && found == store.clusters.end()) return nullptr;

  const uint32_t words = uint32_t((src.sample_count + 63) / 64);
  size_t wanted = receivers.size() * (sizeof(uint32_t) + sizeof(std::vector<uint64_t>)) +
                  src.sample_count * (sizeof(uint32_t) + 3 * sizeof(float));
  for (uint32_t p : receivers) {
    wanted += mesh.polygons[p].vertex_count() * (1 + words) * sizeof(uint64_t);
  }
  const auto fits = [&] {
    const size_t held = found == store.clusters.end() ? 0 : found->second.bytes;
    return store.bytes - held + wanted <= max_bytes;
  };
  if (!fits()) {
    // Make room from the clusters that have not shot for a while: they may never again.
    for (auto it = store.clusters.begin(); it != store.clusters.end();) {
      if (it->first != src.cluster && shot - store.last_shot[size_t(it->first)] > kKeptWithin) {
        store.bytes -= it->second.bytes;
        it = store.clusters.erase(it);
      } else {
        ++it;
      }
    }
    found = store.clusters.find(src.cluster);
    if (!fits()) {
      // This cluster's answers have outgrown the memory left (its receivers subdivide): they
      // would never fit again.
      if (found != store.clusters.end()) {
        store.bytes -= found->second.bytes;
        store.clusters.erase(found);
      }
      return nullptr;
    }
  }
  KeptRays& k = found == store.clusters.end() ? store.clusters[src.cluster] : found->second;
  // The samples are geometry too, but the answers are only good for the same samples.
  if (k.words != words || k.moved.size() != src.sample_count) {
    store.bytes -= k.bytes;
    k = KeptRays{};
    k.words = words;
    k.moved.assign(src.sample_count, 0);
    k.end_x.assign(src.sample_count, 0.0f);
    k.end_y = k.end_x, k.end_z = k.end_x;
  }
  if (!std::equal(k.receivers.begin(), k.receivers.end(), receivers.begin(), receivers.end())) {
    // Another list (the roulette's draw, a subdivided neighbour, an edit): the polygons on both
    // keep their answers (a vertex's rays are the same segments), the others start untraced.
    // Both lists are in index order.
    assert(std::is_sorted(receivers.begin(), receivers.end()));
    std::vector<std::vector<uint64_t>> answers(receivers.size());
    size_t j = 0;
    for (size_t i = 0; i < receivers.size(); ++i) {
      while (j < k.receivers.size() && k.receivers[j] < receivers[i]) ++j;
      if (j < k.receivers.size() && k.receivers[j] == receivers[i]) {
        answers[i] = std::move(k.answers[j]);
      }
    }
    k.answers = std::move(answers);
    // A fresh copy: no capacity left uncounted.
    k.receivers = std::vector<uint32_t>(receivers.begin(), receivers.end());
  }
  ++k.epoch;
  for (size_t g = 0; g < src.sample_count; ++g) {
    if (k.epoch == 1 || src.end_x[g] != k.end_x[g] || src.end_y[g] != k.end_y[g] ||
        src.end_z[g] != k.end_z[g]) {
      k.moved[g] = k.epoch;
      k.end_x[g] = src.end_x[g], k.end_y[g] = src.end_y[g], k.end_z[g] = src.end_z[g];
    }
  }
  k.answers.resize(receivers.size());
  for (size_t i = 0; i < receivers.size(); ++i) {
    // Vertices made since the last shot start at epoch 0: never traced. Reserved exactly (a
    // vector's growth would hold up to twice as much), so `wanted` is what is held.
    const size_t n = mesh.polygons[receivers[i]].vertex_count() * (1 + words);
    k.answers[i].reserve(n);
    k.answers[i].resize(n, 0);
  }
  store.bytes = store.bytes - k.bytes + wanted;
  k.bytes = wanted;
  return &k;
}

}  // namespace rad
