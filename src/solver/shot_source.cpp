#include "solver/shot_source.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/sample_points.h"
#include "solver/solver_state.h"
#include "visibility/segment.h"

namespace rad {

namespace {
// Where, in longest source edges, single-precision contours stop and the far field starts;
// errors measured by tests/solver/gather_test.cpp.
constexpr float kSingleEdges = 6.0f;
constexpr float kFarFieldEdges = 6.0f;
}  // namespace

void SampleLanes::push_back(const Vec3& p, const Vec3& u) {
  x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  r.push_back(u.x), g.push_back(u.y), b.push_back(u.z);
  live.push_back(1.0f);
}

void SampleLanes::pad() {
  while (size() % kLanes != 0) {
    push_back(Vec3(0.0f), Vec3(0.0f));
    live.back() = 0.0f;
  }
}

const SampleGrid& sample_grid_for(const SolverState& s, float longest_edge) {
  // The least m whose sample spacing (longest edge / m) is within the initial mesh's size.
  const float first = float(s.sample_grids.front().m), last = float(s.sample_grids.back().m);
  const float wanted = s.max_size > 0.0f ? std::ceil(longest_edge / s.max_size) : first;
  return s.sample_grids[size_t(std::clamp(wanted, first, last) - first)];
}

ShotSource make_shot_source(const SolverState& s, int32_t p) {
  const Triangles& tris = s.hierarchy->triangles;
  const PolygonMesh& mesh = s.mesh.polygons[size_t(p)];
  ShotSource src;
  src.polygon = p;
  for (int k = 0; k < 3; ++k) src.corner[k] = tris.corners[size_t(p)][k];
  src.normal = tris.normal[size_t(p)];
  src.area = tris.area[size_t(p)];
  float longest = 0.0f;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(longest, glm::length(src.corner[(k + 1) % 3] - src.corner[k]));
  }
  src.longest_edge = longest;
  const SampleGrid& grid = sample_grid_for(s, longest);
  const std::vector<Vec3>& bary = grid.coarse;
  src.area_per_sample = src.area / float(bary.size());
  for (const Vec3& w : bary) {
    const Vec3 u = interpolate_at(mesh, &MeshVertex::unshot, w);
    const Vec3 q = src.corner[0] * w.x + src.corner[1] * w.y + src.corner[2] * w.z;
    src.sample.push_back(q, u);
    src.mean_unshot += u;
    const Vec3 end = off_surface(q, src.normal, s.shadow_offset);
    src.end_x.push_back(end.x), src.end_y.push_back(end.y), src.end_z.push_back(end.z);
  }
  src.sample_count = bary.size();
  src.sample.pad();
  src.centroid = (src.corner[0] + src.corner[1] + src.corner[2]) * (1.0f / 3.0f);
  src.mean_unshot /= float(bary.size());
  // Near field: closer than two coarse sample spacings (longest edge / m).
  const int m = grid.m, k = m / 2;
  src.near_distance = 2.0f * longest / float(m);
  src.single_distance = kSingleEdges * longest;
  src.far_distance = kFarFieldEdges * longest;
  if (k >= 1) {
    for (const Vec3& w : grid.half) {
      src.coarse_sample.push_back(src.corner[0] * w.x + src.corner[1] * w.y + src.corner[2] * w.z,
                                  Vec3(0.0f));
    }
    src.coarse_count = size_t(k) * size_t(k);
    src.coarse_sample.pad();
    const float m2 = float(m * m), k2 = float(k * k);
    src.richardson_fine = m2 / (m2 - k2) * src.area_per_sample;
    src.richardson_coarse = k2 / (m2 - k2) * (src.area / k2);
  } else {
    src.far_distance = std::numeric_limits<float>::infinity();  // one sample: no extrapolation
  }
  src.fine_area_per_sample = src.area / float(grid.fine.size());
  for (size_t c = 0; c < bary.size(); ++c) {
    for (size_t i = grid.fine_begin[c]; i < grid.fine_begin[c + 1]; ++i) {
      const Vec3& w = grid.fine[i];
      src.fine_sample.push_back(src.corner[0] * w.x + src.corner[1] * w.y + src.corner[2] * w.z,
                                interpolate_at(mesh, &MeshVertex::unshot, w));
    }
    src.fine_sample.pad();
    src.fine_group_parent.resize(src.fine_sample.size() / SampleLanes::kLanes, uint32_t(c));
  }
  return src;
}

}  // namespace rad
