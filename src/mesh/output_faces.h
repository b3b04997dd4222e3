// Crack-free triangles over the leaf elements of a polygon (T-vertices included).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/patch_mesh.h"

namespace rad {

/// The faces to write for one polygon. Indices below the polygon's vertex count name its
/// vertices; index vertex_count + k names centroids[k], an extra vertex at the mean of three
/// polygon vertices (its value is their mean too, which is what Gouraud shading shows there).
struct PolygonFaces {
  std::vector<uint32_t> triangles;  // 3 indices per face, same orientation as the polygon
  std::vector<std::array<uint32_t, 3>> centroids;
};

/// Triangulates every leaf of `p`. A leaf with a neighbour's midpoint on its edge (a
/// T-vertex) is split through that vertex so the written faces have no cracks: fanned from the
/// opposite corner when only one edge carries such vertices, from an added centroid otherwise.
PolygonFaces triangulate_leaves(const PolygonMesh& p);

}  // namespace rad
