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
  // Near field: receivers closer to the source's plane than `near_distance` weight its unshot
  // radiosity over 16x more samples (no more rays: each fine sample takes the visibility of
  // the coarse sample whose cell holds it), so a big source's variation is not read off the one
  // or two coarse samples that dominate the kernel up close.
  float near_distance = 0.0f;
  float fine_area_per_sample = 0.0f;
  std::vector<Vec3> fine_sample, fine_unshot;
  std::vector<uint32_t> fine_parent;  // coarse sample of each fine one
};

/// Freezes polygon p as the source of the next shot: the state's n = m*m regular samples
/// (SPEC §4) and the 16x finer near-field ones, each with the unshot radiosity interpolated from
/// the vertices of the leaf element it lies in.
ShotSource make_shot_source(const SolverState& s, int32_t p);

}  // namespace rad
