#include "solver/kept_rays.h"

#include "solver/solver_state.h"

namespace rad {

KeptRays* prepare_kept_rays(SolverState& s, const ShotSource& src) {
  if (s.options.kept_rays_bytes == 0 || src.sample_count == 0) return nullptr;
  const auto [it, first_shot] = s.kept_rays.try_emplace(src.cluster);
  if (first_shot) return nullptr;
  KeptRays& k = it->second;
  const uint32_t words = uint32_t((src.sample_count + 63) / 64);
  size_t wanted = s.receivers.size() * (sizeof(uint32_t) + sizeof(std::vector<uint64_t>));
  for (uint32_t p : s.receivers) {
    wanted += s.mesh.polygons[p].vertex_count() * (1 + words) * sizeof(uint64_t);
  }
  const size_t held = k.bytes;
  if (s.kept_rays_bytes - held + wanted > s.options.kept_rays_bytes) return nullptr;
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
