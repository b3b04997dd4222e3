#include "solver/shot_source.h"

#include <algorithm>

#include "mesh/sample_points.h"
#include "solver/solver_state.h"

namespace rad {

ShotSource make_shot_source(const SolverState& s, int32_t p) {
  const std::vector<Vec3>& bary = s.sample_barycentrics;
  const Triangles& tris = s.hierarchy->triangles;
  const PolygonMesh& mesh = s.mesh.polygons[size_t(p)];
  ShotSource src;
  src.polygon = p;
  for (int k = 0; k < 3; ++k) src.corner[k] = tris.corners[size_t(p)][k];
  src.normal = tris.normal[size_t(p)];
  src.area = tris.area[size_t(p)];
  src.area_per_sample = src.area / float(bary.size());
  src.sample.reserve(bary.size());
  src.unshot.reserve(bary.size());
  for (const Vec3& w : bary) {
    src.sample.push_back(src.corner[0] * w.x + src.corner[1] * w.y + src.corner[2] * w.z);
    src.unshot.push_back(interpolate_at(mesh, &MeshVertex::unshot, w));
    src.mean_unshot += src.unshot.back();
  }
  src.mean_unshot /= float(bary.size());
  // Near field: closer than two coarse sample spacings (longest edge / m).
  float longest = 0.0f;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(longest, glm::length(src.corner[(k + 1) % 3] - src.corner[k]));
  }
  src.near_distance = 2.0f * longest / float(s.options.sample_grid);
  src.fine_area_per_sample = src.area / float(s.fine_barycentrics.size());
  src.fine_parent = s.fine_parent;
  for (const Vec3& w : s.fine_barycentrics) {
    src.fine_sample.push_back(src.corner[0] * w.x + src.corner[1] * w.y + src.corner[2] * w.z);
    src.fine_unshot.push_back(interpolate_at(mesh, &MeshVertex::unshot, w));
  }
  return src;
}

}  // namespace rad
