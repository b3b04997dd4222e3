// What the solver derives from the scene once (and keeps current as the mesh refines): the
// shooting clusters, the shared and the buried vertices, occlusion culling, the element sizes.
#pragma once

#include <vector>

#include "core/math.h"
#include "scene/light.h"
#include "solver/buried_vertices.h"
#include "solver/clusters.h"
#include "solver/occlusion_culling.h"
#include "solver/shared_vertices.h"

namespace rad {

struct SceneCaches {
  /// The shooting patches (design §10), of at most (max_sample_grid x max_size)^2 each.
  Clusters clusters;
  SharedVertices shared;
  /// The vertices inside solids and where they gather instead (buried_vertices.h): found at
  /// the first step, when a visibility backend is at hand, and for new vertices as they are made.
  BuriedVertices buried;
  /// The flat occluders and the tree over the triangles that cull receivers hidden from a source
  /// (empty without shadows).
  OcclusionCulling culling;
  /// The scene's lights as they shoot (light_source.h: shooting_lights), which their shots'
  /// sources point to.
  std::vector<Light> shooting_lights;
  float min_size = 0.0f;  // smallest element edge
  float max_size = 0.0f;  // largest element edge of the initial mesh
  float shadow_offset = 0.0f;
  /// regular_sample_barycentrics(q) for q = 1 .. 4 x max_sample_grid (index q; 0 is empty):
  /// where a source's triangles are cut into fine points.
  std::vector<std::vector<Vec3>> barycentric_grids;
};

/// How vertices inside solids are probed (buried_vertices.h): a vertex moves at most the smallest
/// elements' size, as far as the last elements that reach out of a solid extend.
inline BuriedProbe buried_probe(const SceneCaches& scene) {
  return {scene.shadow_offset, scene.min_size};
}

/// The smallest size an element may have and still split: its children keep sizes >= min_size.
inline float min_split_size(const SceneCaches& scene) { return 2.0f * scene.min_size; }

/// Whether vertex v of polygon p, at `x`, reflects what it gathers into the light it shoots
/// (BuriedVertices::shoots).
inline float shooting_reach(const SceneCaches& scene) { return kShootingDepth * scene.min_size; }
inline bool vertex_shoots(const SceneCaches& scene, size_t p, uint32_t v, const Vec3& x) {
  return scene.buried.shoots(p, v, x, shooting_reach(scene));
}

}  // namespace rad
