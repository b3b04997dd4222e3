// A shooting polygon frozen for one shot: its geometry and its samples' unshot radiosity.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace rad {

struct SolverState;

struct ShotSource {
  int32_t polygon = -1;
  Vec3 corner[3];
  Vec3 normal;
  float area = 0.0f;
  float area_per_sample = 0.0f;  // A / n
  std::vector<Vec3> sample;      // sample points on the source
  std::vector<Vec3> unshot;      // the source's unshot radiosity at each sample
  Vec3 mean_unshot{0.0f};        // area-weighted mean unshot radiosity over the samples
  bool major = false;            // carried >= major_shot_fraction of the emitted energy
};

/// Freezes polygon p as the source of the next shot: n = m*m regular samples (SPEC §4), each
/// with the unshot radiosity interpolated from the vertices of the leaf element it lies in.
ShotSource make_shot_source(const SolverState& s, int32_t p, const std::vector<Vec3>& barycentrics);

}  // namespace rad
