// 3D DDA (Amanatides & Woo): order of cells, axis rays, corners, inside/outside starts, early exit.
#include "visibility/grid_walker.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

namespace rad {
namespace {

using Cell = std::array<int, 3>;

Vec3 inverse(const Vec3& d) { return Vec3(1.0f / d.x, 1.0f / d.y, 1.0f / d.z); }

// All cells walked by the segment origin → origin + direction, clipped to the grid box.
std::vector<Cell> walk(const GridShape& g, Vec3 origin, Vec3 direction) {
  std::vector<Cell> cells;
  Vec3 inv = inverse(direction);
  float t0 = 0.0f, t1 = 1.0f;
  if (!clip_segment_to_box(g.lo, g.hi, origin, inv, t0, t1)) return cells;
  walk_grid(g, origin, direction, inv, t0, t1, [&](const GridCell& c) {
    EXPECT_EQ(c.index, g.index(c.x, c.y, c.z));
    cells.push_back({c.x, c.y, c.z});
    return false;
  });
  return cells;
}

TEST(GridWalker, AlongPositiveXFromOutside) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(4, 1, 1), {4, 1, 1});
  EXPECT_EQ(walk(g, Vec3(-1, 0.5f, 0.5f), Vec3(6, 0, 0)),
            (std::vector<Cell>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}));
}

TEST(GridWalker, AlongNegativeYAndZ) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(1, 3, 3), {1, 3, 3});
  EXPECT_EQ(walk(g, Vec3(0.5f, 5, 0.5f), Vec3(0, -10, 0)),
            (std::vector<Cell>{{0, 2, 0}, {0, 1, 0}, {0, 0, 0}}));
  EXPECT_EQ(walk(g, Vec3(0.5f, 1.5f, 2.5f), Vec3(0, 0, -2)),
            (std::vector<Cell>{{0, 1, 2}, {0, 1, 1}, {0, 1, 0}}));
}

TEST(GridWalker, StartsInsideAndStopsAtSegmentEnd) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(4, 4, 4), {4, 4, 4});
  EXPECT_EQ(walk(g, Vec3(1.5f, 2.5f, 0.5f), Vec3(1.0f, 0, 0)),
            (std::vector<Cell>{{1, 2, 0}, {2, 2, 0}}));
  // Entirely inside one cell.
  EXPECT_EQ(walk(g, Vec3(1.2f, 1.2f, 1.2f), Vec3(0.5f, 0.5f, 0.5f)),
            (std::vector<Cell>{{1, 1, 1}}));
}

TEST(GridWalker, ThroughCornersVisitsTheDiagonal) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(3, 3, 3), {3, 3, 3});
  std::vector<Cell> cells = walk(g, Vec3(-1, -1, -1), Vec3(5, 5, 5));
  ASSERT_GE(cells.size(), 3u);
  EXPECT_EQ(cells.front(), (Cell{0, 0, 0}));
  EXPECT_EQ(cells.back(), (Cell{2, 2, 2}));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NE(std::find(cells.begin(), cells.end(), Cell{k, k, k}), cells.end()) << k;
  }
}

TEST(GridWalker, MissingTheBoxVisitsNothing) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(1), {2, 2, 2});
  EXPECT_TRUE(walk(g, Vec3(2, 2, 2), Vec3(1, 0, 0)).empty());
  EXPECT_TRUE(walk(g, Vec3(-2, 0.5f, 0.5f), Vec3(1, 0, 0)).empty());  // stops short
}

TEST(GridWalker, EarlyExitStopsTheWalk) {
  GridShape g = make_grid_shape(Vec3(0), Vec3(8, 1, 1), {8, 1, 1});
  int visited = 0;
  Vec3 o(-1, 0.5f, 0.5f), d(10, 0, 0);
  bool hit = walk_grid(g, o, d, inverse(d), 0.1f, 0.9f, [&](const GridCell& c) {
    ++visited;
    return c.x == 2;
  });
  EXPECT_TRUE(hit);
  EXPECT_EQ(visited, 3);
}

// Random segments through random grids: every cell that a point of the segment lies in (sampled
// densely, away from cell boundaries) is visited, in order, and consecutive cells touch.
TEST(GridWalker, RandomSegmentsVisitEveryCrossedCellInOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int iteration = 0; iteration < 2000; ++iteration) {
    std::array<int32_t, 3> res{1 + int(rng() % 9), 1 + int(rng() % 9), 1 + int(rng() % 9)};
    Vec3 lo(u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 2);
    Vec3 hi = lo + Vec3(0.5f + 3 * u(rng), 0.5f + 3 * u(rng), 0.5f + 3 * u(rng));
    GridShape g = make_grid_shape(lo, hi, res);
    Vec3 a =
        lo + (hi - lo) * Vec3(u(rng) * 1.6f - 0.3f, u(rng) * 1.6f - 0.3f, u(rng) * 1.6f - 0.3f);
    Vec3 b =
        lo + (hi - lo) * Vec3(u(rng) * 1.6f - 0.3f, u(rng) * 1.6f - 0.3f, u(rng) * 1.6f - 0.3f);
    if (iteration % 5 == 0) b[iteration % 3] = a[iteration % 3];  // axis-parallel cases
    std::vector<Cell> cells = walk(g, a, b - a);
    for (size_t k = 1; k < cells.size(); ++k) {
      int manhattan = 0;
      for (int axis = 0; axis < 3; ++axis)
        manhattan += std::abs(cells[k][axis] - cells[k - 1][axis]);
      ASSERT_EQ(manhattan, 1) << "iteration " << iteration;
    }
    size_t cursor = 0;
    for (int s = 1; s < 400; ++s) {
      Vec3 p = a + (b - a) * (float(s) / 400.0f);
      Vec3 q = (p - g.lo) * g.inv_cell_size;
      bool inside = true, near_boundary = false;
      Cell c;
      for (int axis = 0; axis < 3; ++axis) {
        inside &= q[axis] >= 0.0f && q[axis] < float(res[axis]);
        near_boundary |= std::abs(q[axis] - std::round(q[axis])) < 1e-3f;
        c[axis] = int(std::floor(q[axis]));
      }
      if (!inside || near_boundary) continue;
      while (cursor < cells.size() && cells[cursor] != c) ++cursor;
      ASSERT_LT(cursor, cells.size()) << "iteration " << iteration << " sample " << s;
    }
  }
}

TEST(ClipSegmentToBox, ClipsToTheSlabs) {
  Vec3 o(-1, 0.5f, 0.5f), d(4, 0, 0);
  float t0 = 0.0f, t1 = 1.0f;
  ASSERT_TRUE(clip_segment_to_box(Vec3(0), Vec3(1), o, inverse(d), t0, t1));
  EXPECT_FLOAT_EQ(t0, 0.25f);
  EXPECT_FLOAT_EQ(t1, 0.5f);
  // Parallel to a slab and outside it: empty.
  t0 = 0.0f, t1 = 1.0f;
  EXPECT_FALSE(clip_segment_to_box(Vec3(0), Vec3(1), Vec3(-1, 2, 0.5f), inverse(d), t0, t1));
  // Flat box (zero thickness) crossed perpendicularly.
  Vec3 down(0, 0, -2);
  t0 = 0.0f, t1 = 1.0f;
  EXPECT_TRUE(clip_segment_to_box(Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0.5f, 0.5f, 1), inverse(down),
                                  t0, t1));
}

}  // namespace
}  // namespace rad
