// How the hierarchy's triangles touch: corners welded by position within each Pure, the
// neighbour across each edge, edge-connected regions of alike normals and their outlines. The
// solver's shooting clusters and the visibility's merged occluders are both made of these.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"

namespace rad {

/// Normals within 0.1 degree of each other count as one plane: cos(0.1 degree).
inline constexpr float kPlanarCos = 0.99999847691f;

/// Vertex ids per triangle corner: corners at exactly the same position within one Pure share
/// an id (-0 and +0 alike).
std::vector<std::array<uint32_t, 3>> weld_corners(const Triangles& t);

/// The triangle across each edge (k, k+1) of every triangle, or -1: manifold edges only (used
/// by exactly two triangles, in opposite directions).
std::vector<std::array<int32_t, 3>> edge_neighbours(const std::vector<std::array<uint32_t, 3>>& v);

/// Edge-connected regions of one Pure grown breadth-first from the lowest unassigned triangle,
/// taking neighbours whose normal is within `cos_limit` of the seed's, over the triangles with
/// free[i] set (cleared as they are taken). Regions are appended to `out`, flat, with their
/// starts appended to `starts`.
void grow_regions(const Triangles& t, const std::vector<std::array<int32_t, 3>>& nb,
                  float cos_limit, std::vector<uint8_t>& free, std::vector<uint32_t>& out,
                  std::vector<uint32_t>& starts);

/// A directed edge of a region's boundary: welded vertex ids and positions.
struct BoundaryEdge {
  uint32_t a, b;
  Vec3 pa, pb;
};

/// The edges of the region's triangles used by one of them only (no reverse edge in the
/// region), in the triangles' order.
std::vector<BoundaryEdge> boundary_edges(const Triangles& t,
                                         const std::vector<std::array<uint32_t, 3>>& v,
                                         const std::vector<uint32_t>& tris);

/// The boundary edges with collinear runs merged, appended to ea -> eb.
void outline(const std::vector<BoundaryEdge>& bnd, std::vector<Vec3>& ea, std::vector<Vec3>& eb);

}  // namespace rad
