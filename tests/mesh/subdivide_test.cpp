#include "mesh/subdivide.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh_fixtures.h"

namespace rad {
namespace {

TEST(Subdivide, SplitsIntoFourChildrenOfAQuarterAreaWithThreeNewMidpoints) {
  PolygonMesh p = testing::one_polygon();
  NewMidpoint created[3];
  ASSERT_EQ(split_element(p, 0, created), 3);
  EXPECT_EQ(p.vertex_count(), 6u);
  ASSERT_EQ(p.elements.size(), 5u);
  EXPECT_EQ(p.elements[0].first_child, 1);
  for (int c = 1; c <= 4; ++c) {
    EXPECT_TRUE(p.elements[c].leaf());
    EXPECT_FLOAT_EQ(p.elements[c].area, 0.125f);
  }
  for (const NewMidpoint& m : created) {
    EXPECT_EQ(p.positions[m.vertex], (p.positions[m.a] + p.positions[m.b]) * 0.5f);
  }
}

TEST(Subdivide, ChildrenKeepTheParentOrientation) {
  PolygonMesh p = testing::one_polygon();
  NewMidpoint created[3];
  split_element(p, 0, created);
  for (int c = 1; c <= 4; ++c) {
    const uint32_t* v = p.elements[c].v;
    const Vec3 n =
        glm::cross(p.positions[v[1]] - p.positions[v[0]], p.positions[v[2]] - p.positions[v[0]]);
    EXPECT_GT(n.z, 0.0f) << "child " << c;
  }
}

TEST(Subdivide, NeighboursShareTheMidpointOfTheirCommonEdge) {
  PolygonMesh p = testing::one_polygon();
  NewMidpoint created[3];
  split_element(p, 0, created);
  // Child 1 (corner a) and child 4 (middle) share the edge between midpoints ab and ca.
  EXPECT_EQ(split_element(p, 1, created), 3);
  EXPECT_EQ(p.vertex_count(), 9u);
  EXPECT_EQ(split_element(p, 4, created), 2) << "the shared edge's midpoint must be reused";
  EXPECT_EQ(p.vertex_count(), 11u);
}

TEST(Subdivide, LongestEdge) {
  PolygonMesh p = testing::one_polygon({0, 0, 0}, {3, 0, 0}, {0, 4, 0});
  EXPECT_FLOAT_EQ(longest_edge(p, 0), 5.0f);
}

TEST(Subdivide, ASliverSplitsByTheLengthItsLightDiffersAlong) {
  // A right isosceles triangle: its size by area, whichever edges differ.
  const PolygonMesh square_half = testing::one_polygon({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_FLOAT_EQ(element_size(square_half, 0), 1.0f);
  EXPECT_FLOAT_EQ(split_size(square_half, 0), 1.0f);
  // A strip 24 long and 0.9 wide (edges 01: 24, 12: the hypotenuse, 20: 0.9): by area it is
  // sqrt(24 x 0.9) = 4.6 across; along its length, the length over sqrt 2.
  const PolygonMesh strip = testing::one_polygon({0, 0, 0}, {24, 0, 0}, {0, 0.9f, 0});
  EXPECT_NEAR(element_size(strip, 0), std::sqrt(24.0f * 0.9f), 1e-4f);
  EXPECT_NEAR(split_size(strip, 0, {true, false, false}), 24.0f / std::sqrt(2.0f), 1e-4f);
  EXPECT_NEAR(split_size(strip, 0), std::hypot(24.0f, 0.9f) / std::sqrt(2.0f), 1e-4f);
  // Differing across its width only: the short edge does not make it bigger than its area.
  EXPECT_NEAR(split_size(strip, 0, {false, false, true}), element_size(strip, 0), 1e-6f);
}

}  // namespace
}  // namespace rad
