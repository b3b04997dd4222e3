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

/// Edge-connected regions of one Pure each, grown breadth-first from the lowest unassigned
/// triangle, taking neighbours whose normal is within `cos_limit` of the seed's; with the welded
/// corners they were found with.
struct Regions {
  /// Vertex ids per triangle corner: corners at exactly the same position within one Pure
  /// share one (-0 and +0 alike).
  std::vector<std::array<uint32_t, 3>> corners;
  std::vector<uint32_t> triangles;  // grouped by region
  std::vector<uint32_t> first;      // per region, and one past the end
  size_t size() const { return first.size() - 1; }
};
Regions find_regions(const Triangles& t, float cos_limit);

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

/// The boundary edges with straight runs merged, appended to ea -> eb: a corner is dropped when
/// the run turns there by under 1e-5 radian or it lies within `tolerance` of the run's line.
void outline(const std::vector<BoundaryEdge>& bnd, double tolerance, std::vector<Vec3>& ea,
             std::vector<Vec3>& eb);

}  // namespace rad
