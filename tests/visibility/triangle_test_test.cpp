// Segment–triangle test of SPEC §6: inside, edges, vertices, open ends, grazing, degenerate.
#include "visibility/triangle_test.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

// a = (1,0,0), b = (0,1,0), c = 0: every quantity below is exact in float.
TriangleRecord unit_triangle() {
  return make_triangle_record({Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0)});
}

bool hits_vertical(const TriangleRecord& r, float x, float y) {
  return segment_hits_triangle(r, Vec3(x, y, -1), Vec3(0, 0, 2));
}

TEST(SegmentHitsTriangle, RecordMatchesSpecFormulas) {
  TriangleRecord r = unit_triangle();
  EXPECT_EQ(r.normal, Vec3(0, 0, 1));
  EXPECT_EQ(r.s_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.s_b, Vec3(0, 1, 0));
  EXPECT_EQ(r.plane_offset, 0.0f);
}

TEST(SegmentHitsTriangle, HitsInsideMissesOutside) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(hits_vertical(r, 0.25f, 0.25f));
  EXPECT_FALSE(hits_vertical(r, 0.75f, 0.75f));
  EXPECT_FALSE(hits_vertical(r, -0.1f, 0.5f));
  EXPECT_FALSE(hits_vertical(r, 0.5f, -0.1f));
}

TEST(SegmentHitsTriangle, EdgesAndVerticesCount) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5f));  // hypotenuse: α + β = 1
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.0f));  // β = 0
  EXPECT_TRUE(hits_vertical(r, 0.0f, 0.5f));  // α = 0
  EXPECT_TRUE(hits_vertical(r, 0.0f, 0.0f));  // c
  EXPECT_TRUE(hits_vertical(r, 1.0f, 0.0f));  // a
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5f + 1e-6f) == false);
  EXPECT_FALSE(hits_vertical(r, -1e-6f, 0.5f));
}

TEST(SegmentHitsTriangle, BothSidesBlock) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, 1), Vec3(0, 0, -2)));
}

TEST(SegmentHitsTriangle, EndsAreOpen) {
  TriangleRecord r = unit_triangle();
  // Starting on the plane (t = 0), ending on it (t = 1), or stopping short: no hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, 0), Vec3(0, 0, 1)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 1)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 0.999f)));
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 1.001f)));
}

TEST(SegmentHitsTriangle, GrazingSegments) {
  TriangleRecord r = unit_triangle();
  // In the plane: parallel, never a hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, 0), Vec3(3, 0, 0)));
  // Parallel just above: no hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, 1e-6f), Vec3(3, 0, 0)));
  // Crossing the plane at a shallow angle inside the triangle: hit; outside: miss.
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(-1, 0.2f, -1e-3f), Vec3(2.6f, 0, 2e-3f)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, -1e-3f), Vec3(0.8f, 0, 2e-3f)));
}

TEST(SegmentHitsTriangle, DegenerateNeverHits) {
  // Collinear corners: zero record.
  TriangleRecord line = make_triangle_record({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)});
  EXPECT_EQ(line.normal, Vec3(0.0f));
  EXPECT_FALSE(segment_hits_triangle(line, Vec3(1, 1, -1), Vec3(0, 0, 2)));
  TriangleRecord point = make_triangle_record({Vec3(1), Vec3(1), Vec3(1)});
  EXPECT_FALSE(segment_hits_triangle(point, Vec3(1, 1, 0), Vec3(0, 0, 2)));
  // A zero-length segment never hits.
  EXPECT_FALSE(segment_hits_triangle(unit_triangle(), Vec3(0.2f, 0.2f, 0), Vec3(0)));
}

TEST(SegmentHitsTriangle, ThinTriangleStillHit) {
  TriangleRecord r = make_triangle_record({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5f, 1e-3f, 0)});
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5e-3f));
  EXPECT_FALSE(hits_vertical(r, 0.5f, 2e-3f));
}

}  // namespace
}  // namespace rad
