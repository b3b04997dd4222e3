// Splitting a subdivision element into four by its edge midpoints (design §5).
#pragma once

#include <array>
#include <cstdint>

#include "mesh/patch_mesh.h"

namespace rad {

/// A midpoint vertex created by split_element, with the edge it halves.
struct NewMidpoint {
  uint32_t vertex;
  uint32_t a, b;
};

/// Splits leaf element `e` of `p` into four children (corner a, corner b, corner c, middle).
/// A midpoint already made by a neighbouring element of the same polygon is reused, so shared
/// vertices exist once. Midpoints created here get the position of the edge's middle; they are
/// written to `created` (up to three) and their count returned. What else a vertex holds is the
/// caller's (the solver grows its vertex states to the new vertex count and sets them).
int split_element(PolygonMesh& p, uint32_t e, NewMidpoint created[3]);

/// Longest edge of element `e`.
float longest_edge(const PolygonMesh& p, uint32_t e);

/// The size of element `e` for the subdivision limits: sqrt(2 x its area), the legs of a right
/// isosceles triangle of its area (about the side of an equilateral one). Unlike the longest
/// edge it does not depend on the triangle's shape, so a tessellation into right triangles
/// refines as deep as one into others of the same area.
float element_size(const PolygonMesh& p, uint32_t e);

/// The size element `e` splits by when its light differs along the edges `along` names (01, 12,
/// 20): element_size, or the longest of those edges over sqrt 2 (a right isosceles triangle's
/// hypotenuse over its legs) when larger. A sliver interpolates its light over its length, not
/// over the width its area gives: real models' slivers 24 cm long and 9 mm wide, across a
/// window's shadow edge, read 1.39 in the middle where the path tracer gives 0.62, and were too
/// small by area to split (tools/bench_rooms bedroom_3_gap). With every edge: the deepest the
/// element may ever split by (solver/memory_estimate.h).
float split_size(const PolygonMesh& p, uint32_t e,
                 const std::array<bool, 3>& along = {true, true, true});

}  // namespace rad
