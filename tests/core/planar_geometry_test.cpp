// Geometry in a plane's frame: clipped areas and containment against hand-computed values.
#include "core/planar_geometry.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

TEST(PlanarGeometry, ATrianglesAreaInsideARectangleIsItsClippedPart) {
  const std::array<DVec2, 3> t{DVec2(0, 0), DVec2(4, 0), DVec2(0, 4)};  // area 8
  EXPECT_DOUBLE_EQ(triangle_area_in_rect(t, DVec2(-1, -1), DVec2(5, 5)), 8.0);
  EXPECT_DOUBLE_EQ(triangle_area_in_rect(t, DVec2(0, 0), DVec2(2, 2)), 4.0);
  // x in [3, 4]: the corner triangle of legs 1 and 1.
  EXPECT_NEAR(triangle_area_in_rect(t, DVec2(3, -1), DVec2(5, 5)), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(triangle_area_in_rect(t, DVec2(5, 5), DVec2(6, 6)), 0.0);
  // Either winding of the clipping polygon.
  const DVec2 square[4] = {DVec2(0, 0), DVec2(0, 2), DVec2(2, 2), DVec2(2, 0)};
  EXPECT_DOUBLE_EQ(triangle_area_inside(t, square, 4), 4.0);
}

TEST(PlanarGeometry, ATriangleHoldsOnlyTheRectanglesWhoseCornersItHolds) {
  const std::array<DVec2, 3> t{DVec2(0, 0), DVec2(4, 0), DVec2(0, 4)};
  EXPECT_TRUE(triangle_holds_rect(t, DVec2(0.5, 0.5), DVec2(1.5, 1.5)));
  EXPECT_FALSE(triangle_holds_rect(t, DVec2(1.5, 1.5), DVec2(2.5, 2.5)));
  const std::array<DVec2, 3> flat{DVec2(0, 0), DVec2(1, 1), DVec2(2, 2)};
  EXPECT_FALSE(triangle_holds_rect(flat, DVec2(1, 1), DVec2(1, 1)));
}

TEST(PlanarGeometry, APlanesFrameIsOrthonormalAndFlatteningKeepsLengths) {
  for (const DVec3 n : {DVec3(0, 0, 1), DVec3(1, 0, 0), glm::normalize(DVec3(1, -2, 3))}) {
    DVec3 u, w;
    plane_frame(n, u, w);
    EXPECT_NEAR(glm::dot(u, u), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(w, w), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(u, w), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(glm::cross(u, w) - n), 0.0, 1e-12);
    const DVec3 o(1, 2, 3);
    const std::array<Vec3, 3> c{Vec3(o), Vec3(o + u * 3.0), Vec3(o + w * 4.0)};
    const auto f = flatten_triangle(o, u, w, c);
    EXPECT_NEAR(glm::length(f[1] - f[2]), 5.0, 1e-5);
    const auto b = bounds_2d(f);
    EXPECT_NEAR(b[1].x - b[0].x, 3.0, 1e-5);
    EXPECT_NEAR(b[1].y - b[0].y, 4.0, 1e-5);
  }
}

}  // namespace
}  // namespace rad
