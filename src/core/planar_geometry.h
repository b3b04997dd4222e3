// Geometry in a plane's own 2-D frame: flattening triangles into it, clipping, areas.
#pragma once

#include <array>
#include <cstddef>
#include <glm/vec2.hpp>

#include "core/math.h"

namespace rad {

using DVec2 = glm::dvec2;

/// Area of the convex polygon a[0 .. n).
double convex_polygon_area(const DVec2* a, size_t n);

/// Area of triangle t inside the convex polygon c[0 .. m) (Sutherland-Hodgman: t clipped by
/// each edge of c in turn; either winding; m <= 13).
double triangle_area_inside(const std::array<DVec2, 3>& t, const DVec2* c, size_t m);

/// Area of triangle t inside the rectangle [lo, hi].
double triangle_area_in_rect(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi);

/// Whether triangle t holds the rectangle [lo, hi] (its four corners); false for a degenerate t.
bool triangle_holds_rect(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi);

/// The corners c in the frame (u, w) of a plane through `origin`.
std::array<DVec2, 3> flatten_triangle(const DVec3& origin, const DVec3& u, const DVec3& w,
                                      const std::array<Vec3, 3>& c);

/// The 2-D box of triangle t: its least and largest corner.
std::array<DVec2, 2> bounds_2d(const std::array<DVec2, 3>& t);

/// A right-handed orthonormal frame (u, w) of the plane with unit normal n (any one).
void plane_frame(const DVec3& n, DVec3& u, DVec3& w);

/// Two uniform draws a, b in [0, 1) folded into the triangle a, b >= 0, a + b <= 1: a point
/// uniform over any triangle as corner + a (edge 1) + b (edge 2).
inline glm::vec2 fold_into_triangle(float a, float b) {
  return a + b > 1.0f ? glm::vec2(1.0f - a, 1.0f - b) : glm::vec2(a, b);
}

}  // namespace rad
