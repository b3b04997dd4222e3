// Triangle–voxel overlap by interval arithmetic on the design §6 expressions (grid construction).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "visibility/grid_walker.h"

namespace rad {

/// A triangle in double precision for the overlap test: c, n = e_a × e_b, and s_a, s_b as in
/// TriangleRecord. `degenerate` when n = 0 (such a triangle is never hit and needs no cell).
struct TriangleFrame {
  DVec3 c{0.0}, n{0.0}, s_a{0.0}, s_b{0.0};
  bool degenerate = true;
};

TriangleFrame make_triangle_frame(const std::array<Vec3, 3>& corners);

/// design §6 overlap by interval arithmetic: the box [lo, hi] is a point whose coordinates are
/// intervals; it may overlap the triangle when the interval of n·(x − c) contains 0 and the
/// intervals of α = (x − c)·s_a, β = (x − c)·s_b and α + β each meet [0, 1]. Each expression is
/// linear with every coordinate appearing once, so each interval is the exact range over the box;
/// the test is conservative (never false for a box that truly overlaps) but may accept a box
/// where the three conditions hold at different points. False for degenerate triangles.
bool triangle_may_overlap_box(const TriangleFrame& t, const DVec3& lo, const DVec3& hi);

/// Appends to `cells` the index of every cell of `grid` that the triangle may overlap: candidates
/// are the cells meeting the triangle's bounding box, each kept if triangle_may_overlap_box
/// accepts the cell grown by `margin` × its size on every side. The margin absorbs float rounding
/// in the walker's cell boundaries, so a segment crossing the triangle always visits a cell that
/// lists it.
void overlapped_cells(const std::array<Vec3, 3>& corners, const GridShape& grid, double margin,
                      std::vector<uint32_t>& cells);

}  // namespace rad
