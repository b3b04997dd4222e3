// Sample points on a source polygon and their place in its subdivision (SPEC §4-5).
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

/// A per-vertex quantity of `p` (the member `field` of its vertices) interpolated at polygon
/// barycentrics `bary` from the vertices of the leaf element holding it.
Vec3 interpolate_at(const PolygonMesh& p, Vec3 MeshVertex::*field, Vec3 bary);

}  // namespace rad
