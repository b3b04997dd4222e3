// A shooting polygon frozen for one shot: its geometry and its samples' unshot radiosity.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace rad {

struct SolverState;
struct SampleGrid;

/// Points on a source and the unshot radiosity there, as a structure of arrays padded to whole
/// groups of kLanes so the kernel loops over them run as fixed-width vector code.
struct SampleLanes {
  static constexpr size_t kLanes = 8;
  std::vector<float> x, y, z;               // position
  std::vector<float> r, g, b;               // unshot radiosity
  std::vector<float> live;                  // 1 for a sample, 0 for padding
  size_t size() const { return x.size(); }  // including padding
  bool empty() const { return x.empty(); }
  void push_back(const Vec3& p, const Vec3& u);
  /// Appends dead lanes up to the next multiple of kLanes.
  void pad();
  Vec3 point(size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 value(size_t i) const { return {r[i], g[i], b[i]}; }
};

struct ShotSource {
  int32_t polygon = -1;
  Vec3 corner[3];
  Vec3 normal;
  float area = 0.0f;
  float area_per_sample = 0.0f;  // A / n
  SampleLanes sample;            // sample points on the source and their unshot radiosity
  size_t sample_count = 0;       // samples in `sample` (its lanes less the padding)
  // Where the shadow rays to the samples end: each sample moved off the source (off_surface
  // with the state's shadow offset), once per shot rather than once per receiving vertex.
  std::vector<float> end_x, end_y, end_z;
  Vec3 mean_unshot{0.0f};        // area-weighted mean unshot radiosity over the samples
  bool major = false;            // carried >= major_shot_fraction of the emitted energy
  // Near field: receivers closer to the source's plane than `near_distance` weight its unshot
  // radiosity over 16x more samples (no more rays: each fine sample takes the visibility of
  // the coarse sample whose cell holds it), so a big source's variation is not read off the one
  // or two coarse samples that dominate the kernel up close.
  float near_distance = 0.0f;
  // How a receiver gets its form factor, by its distance from the centroid: within
  // single_distance the contour integral in single precision, then in double (see
  // form_factor.h); beyond far_distance, when every sample is in front of it, the exact
  // integrand's midpoint rule over the n samples, Richardson-extrapolated with the same rule
  // over the k*k samples of a coarser regular split (k = m/2):
  //   F = (m^2 S_m - k^2 S_k) / (m^2 - k^2),
  // which cancels the rule's (edge / distance)^2 error term.
  Vec3 centroid{0.0f};
  float longest_edge = 0.0f;
  float single_distance = 0.0f, far_distance = 0.0f;
  SampleLanes coarse_sample;  // the k*k points (positions only)
  size_t coarse_count = 0;
  float richardson_fine = 0.0f, richardson_coarse = 0.0f;  // m^2/(m^2-k^2) A/n, k^2/(..) A/k^2
  float fine_area_per_sample = 0.0f;
  // Fine samples grouped by the coarse sample whose cell holds them, each group padded to whole
  // lanes: lanes [kLanes g, kLanes (g + 1)) all lie in coarse sample fine_group_parent[g]'s cell,
  // so a group takes that sample's visibility whole.
  SampleLanes fine_sample;
  std::vector<uint32_t> fine_group_parent;
};

/// The sample grid a source whose longest edge is `longest_edge` gets: the least m in the
/// state's range whose spacing is within the initial mesh's element size.
const SampleGrid& sample_grid_for(const SolverState& s, float longest_edge);

/// Freezes polygon p as the source of the next shot: n = m*m regular samples (SPEC §4, m from
/// sample_grid_for) and the 16x finer near-field ones, each with the unshot radiosity
/// interpolated from the vertices of the leaf element it lies in.
ShotSource make_shot_source(const SolverState& s, int32_t p);

}  // namespace rad
