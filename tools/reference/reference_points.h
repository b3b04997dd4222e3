// Where the reference is evaluated: stratified points on every triangle of a scene.
#pragma once

#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "reference/reference_set.h"

namespace rad {

struct PointOptions {
  uint32_t total = 1500;          // points shared out over the scene in proportion to area
  uint32_t min_per_triangle = 8;  // ... but at least this many on every triangle
  uint64_t seed = 1;
  /// Points are moved inside their triangle: every barycentric coordinate is at least this.
  float inset = 1e-3f;
  /// Instead of the spread points: the three corners of every triangle, each moved inside by
  /// `inset`, where rad's output takes its vertices' own values (no interpolation across an
  /// element): a check of the values rad computes rather than of its mesh.
  bool corners = false;
};

/// Points per triangle: max(min_per_triangle, its points of `total` spread systematically by
/// area over the scene), each within one of total x area / scene area.
std::vector<uint32_t> points_per_triangle(const Triangles& t, const PointOptions& o);

/// Stratified points on every triangle, deterministic for a seed: point i of n on a triangle
/// takes r1 = (i + xi) / n (strata in r1) and r2 = frac(xi' + i / phi) (a golden-ratio
/// sequence), mapped to the triangle by the area-preserving warp u = sqrt(r1)(1 - r2),
/// v = sqrt(r1) r2 (Shirley & Chiu), then shrunk toward the centroid by `inset`.
/// Triangles in index order, points of a triangle contiguous.
std::vector<ReferencePoint> make_reference_points(const Triangles& t, const PointOptions& o);

/// The point (u, v) of triangle `triangle`: position and front normal.
ReferencePoint point_on_triangle(const Triangles& t, int32_t triangle, float u, float v);

}  // namespace rad
