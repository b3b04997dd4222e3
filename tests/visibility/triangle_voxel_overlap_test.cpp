// Triangle–voxel overlap (interval arithmetic, design §6) against an exact separating-axis test.
#include "visibility/triangle_voxel_overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

namespace rad {
namespace {

// Exact (in double) separating-axis test of a triangle against a box: Akenine-Möller, "Fast 3D
// Triangle-Box Overlap Testing", JGT 2001 — 13 axes: the box normals, the triangle normal and the
// 9 cross products of edges with box axes. Touching counts as overlapping.
bool sat_overlap(const std::array<Vec3, 3>& tri, const DVec3& lo, const DVec3& hi) {
  DVec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  DVec3 v[3] = {DVec3(tri[0]) - centre, DVec3(tri[1]) - centre, DVec3(tri[2]) - centre};
  auto separated = [&](const DVec3& axis) {
    double p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
    double r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  DVec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  DVec3 unit[3] = {DVec3(1, 0, 0), DVec3(0, 1, 0), DVec3(0, 0, 1)};
  for (const DVec3& u : unit) {
    if (separated(u)) return false;
  }
  if (separated(glm::cross(e[0], e[1]))) return false;
  for (const DVec3& edge : e) {
    for (const DVec3& u : unit) {
      DVec3 axis = glm::cross(edge, u);
      if (glm::dot(axis, axis) > 0.0 && separated(axis)) return false;
    }
  }
  return true;
}

TEST(TriangleVoxelOverlap, NeverMissesAnOverlapOnRandomCases) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int kCases = 200000;
  int exact = 0, interval = 0, missed = 0;
  for (int i = 0; i < kCases; ++i) {
    // Triangles of random size around the unit box, some slivers.
    float size = (i % 4 == 0) ? 0.2f : 1.5f;
    Vec3 centre(u(rng) * 2.0f - 0.5f, u(rng) * 2.0f - 0.5f, u(rng) * 2.0f - 0.5f);
    std::array<Vec3, 3> tri;
    for (Vec3& p : tri) p = centre + size * Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    if (i % 10 == 0) tri[2] = tri[0] + (tri[1] - tri[0]) * 0.5f + Vec3(1e-3f, 0, 0);  // sliver
    DVec3 lo(0.0), hi(1.0);
    bool a = sat_overlap(tri, lo, hi);
    bool b = triangle_may_overlap_box(make_triangle_frame(tri), lo, hi);
    exact += a;
    interval += b;
    if (a && !b) ++missed;
  }
  std::printf(
      "[ overlap  ] %d random cases: %d overlap exactly, interval test accepts %d "
      "(%d extra candidates, %.1f%% of the true overlaps), %d missed\n",
      kCases, exact, interval, interval - exact, 100.0 * (interval - exact) / std::max(exact, 1),
      missed);
  EXPECT_EQ(missed, 0);
  EXPECT_GE(interval, exact);
}

TEST(TriangleVoxelOverlap, AxisAlignedCases) {
  TriangleFrame t = make_triangle_frame({Vec3(0, 0, 0.5f), Vec3(1, 0, 0.5f), Vec3(0, 1, 0.5f)});
  EXPECT_TRUE(triangle_may_overlap_box(t, DVec3(0), DVec3(1)));
  EXPECT_FALSE(triangle_may_overlap_box(t, DVec3(0, 0, 0.6), DVec3(1, 1, 1)));    // above plane
  EXPECT_FALSE(triangle_may_overlap_box(t, DVec3(0.8, 0.8, 0), DVec3(1, 1, 1)));  // past hypotenuse
  EXPECT_TRUE(triangle_may_overlap_box(t, DVec3(0.4, 0.4, 0), DVec3(1, 1, 1)));   // touches it
}

TEST(TriangleVoxelOverlap, DegenerateTriangleGetsNoCell) {
  TriangleFrame t = make_triangle_frame({Vec3(0), Vec3(1), Vec3(2)});
  EXPECT_TRUE(t.degenerate);
  EXPECT_FALSE(triangle_may_overlap_box(t, DVec3(-10), DVec3(10)));
}

// Every cell holding a point of the triangle is listed.
TEST(TriangleVoxelOverlap, OverlappedCellsCoverTheTriangle) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  GridShape g = make_grid_shape(Vec3(0), Vec3(1), {7, 5, 6});
  for (int i = 0; i < 500; ++i) {
    std::array<Vec3, 3> tri;
    for (Vec3& p : tri) p = Vec3(u(rng), u(rng), u(rng));
    std::vector<uint32_t> cells;
    overlapped_cells(tri, g, 1e-4, cells);
    for (int s = 0; s < 200; ++s) {
      float a = u(rng), b = u(rng);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      Vec3 p = tri[2] + a * (tri[0] - tri[2]) + b * (tri[1] - tri[2]);
      Vec3 q = (p - g.lo) * g.inv_cell_size;
      uint32_t index = g.index(std::clamp(int(q.x), 0, 6), std::clamp(int(q.y), 0, 4),
                               std::clamp(int(q.z), 0, 5));
      ASSERT_NE(std::find(cells.begin(), cells.end(), index), cells.end()) << i << " " << s;
    }
  }
}

}  // namespace
}  // namespace rad
