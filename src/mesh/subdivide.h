// Splitting a subdivision element into four by its edge midpoints (design §5).
#pragma once

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

}  // namespace rad
