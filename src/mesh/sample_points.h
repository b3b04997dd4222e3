// Sample points on a source polygon and their place in its subdivision (design §4-5).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/patch_mesh.h"

namespace rad {

/// Barycentric coordinates (weights of corners a, b, c) of the centroids of the m*m congruent
/// sub-triangles of a regular split of the triangle: n = m*m samples spread regularly and
/// uniformly, each standing for area A/n.
std::vector<Vec3> regular_sample_barycentrics(int m);

/// The leaf element of `p` holding the point with polygon barycentrics `bary`, and the
/// point's barycentrics within that leaf. Follows the 1->4 split order of split_element.
uint32_t locate_leaf(const PolygonMesh& p, Vec3 bary, Vec3* leaf_bary);

/// A per-vertex quantity of `p` (value: of a vertex index) interpolated at polygon barycentrics
/// `bary` from the vertices of the leaf element holding it.
template <typename Value>
Vec3 interpolate_at(const PolygonMesh& p, Value&& value, Vec3 bary) {
  Vec3 w;
  const Element& el = p.elements[locate_leaf(p, bary, &w)];
  return value(el.v[0]) * w.x + value(el.v[1]) * w.y + value(el.v[2]) * w.z;
}

}  // namespace rad
