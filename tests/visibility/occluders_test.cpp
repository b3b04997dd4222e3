// Flat regions merged for the shadow rays: what merges, what is kept, and the same answers.
#include "visibility/occluders.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "visibility/backend.h"
#include "visibility/triangle_test.h"

namespace rad {
namespace {

using Tri = std::array<Vec3, 3>;

// Cells [x0, x1) x [y0, y1) of the unit grid at height z, two triangles each, front +z, except
// the cells `skip` says to leave out.
template <typename Skip>
std::vector<Tri> cells(int x0, int x1, int y0, int y1, float z, Skip skip) {
  std::vector<Tri> t;
  for (int i = x0; i < x1; ++i) {
    for (int j = y0; j < y1; ++j) {
      if (skip(i, j)) continue;
      const Vec3 a(float(i), float(j), z), b(float(i + 1), float(j), z),
          c(float(i + 1), float(j + 1), z), d(float(i), float(j + 1), z);
      t.push_back({a, b, c});
      t.push_back({a, c, d});
    }
  }
  return t;
}
std::vector<Tri> grid(int n, float z) {
  return cells(0, n, 0, n, z, [](int, int) { return false; });
}

Hierarchy scene_of(std::vector<std::vector<Tri>> pures) {
  SceneDescription s;
  s.name = "test";
  for (size_t k = 0; k < pures.size(); ++k) {
    ObjectDescription o;
    o.name = "p" + std::to_string(k);
    o.kind = ObjectKind::Pure;
    o.material.reflectance = Vec3(0.5f);
    o.triangles = std::move(pures[k]);
    s.roots.push_back(int32_t(s.objects.size()));
    s.objects.push_back(std::move(o));
  }
  return build_hierarchy(s);
}

double total_area(const Hierarchy& h, uint32_t first, uint32_t count) {
  double a = 0.0;
  for (uint32_t i = first; i < first + count; ++i) a += h.triangles.area[i];
  return a;
}

TEST(MergeFlatRegions, ATessellatedSquareBecomesTwoTrianglesOfTheSameAreaAndObject) {
  const Hierarchy h = scene_of({grid(8, 0.0f), grid(3, 2.0f)});
  const std::optional<Hierarchy> m = merge_flat_regions(h);
  ASSERT_TRUE(m);
  ASSERT_EQ(m->triangles.size(), 4u);
  for (size_t o = 0; o < 2; ++o) {
    const SceneObject &before = h.objects[o], &after = m->objects[o];
    EXPECT_EQ(after.triangle_count, 2u);
    EXPECT_NEAR(total_area(*m, after.first_triangle, after.triangle_count),
                total_area(h, before.first_triangle, before.triangle_count), 1e-4);
    for (uint32_t i = after.first_triangle; i < after.first_triangle + 2; ++i) {
      EXPECT_EQ(m->triangles.object[i], int32_t(o));
      EXPECT_GT(m->triangles.normal[i].z, 0.99f);  // the front kept
    }
  }
}

TEST(MergeFlatRegions, ATurnedAndMovedSquareMergesDespiteItsRounding) {
  // Turned 30 degrees about y and 20 about x, then moved far off: its points leave the lines and
  // the plane they were on by a rounding error of their coordinates.
  std::vector<Tri> square = grid(16, 0.0f);
  const float cy = std::cos(0.5236f), sy = std::sin(0.5236f), cx = std::cos(0.3491f),
              sx = std::sin(0.3491f);
  for (Tri& t : square) {
    for (Vec3& p : t) {
      p = Vec3(cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z);
      p = Vec3(p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z);
      p = p * 0.03f + Vec3(5.0f, -2.0f, 3.0f);
    }
  }
  const Hierarchy h = scene_of({square});
  const std::optional<Hierarchy> m = merge_flat_regions(h);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->triangles.size(), 2u);
  EXPECT_NEAR(total_area(*m, 0, 2), total_area(h, 0, uint32_t(h.triangles.size())), 1e-6);
}

TEST(MergeFlatRegions, AnLShapedRegionIsClippedIntoEarsThatCoverItExactly) {
  // The 4 x 4 grid less its top-right 2 x 2: a non-convex loop of six corners.
  const Hierarchy h =
      scene_of({cells(0, 4, 0, 4, 0.0f, [](int i, int j) { return i >= 2 && j >= 2; })});
  const std::optional<Hierarchy> m = merge_flat_regions(h);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->triangles.size(), 4u);
  EXPECT_NEAR(total_area(*m, 0, 4), 12.0, 1e-5);
  // A point of the missing corner is covered by no triangle.
  const Segment through{{3.0f, 3.0f, -1.0f}, {0.0f, 0.0f, 2.0f}};
  const Segment inside{{1.0f, 3.0f, -1.0f}, {0.0f, 0.0f, 2.0f}};
  int hits_through = 0, hits_inside = 0;
  for (const TriangleRecord& r : make_triangle_records(*m)) {
    hits_through += segment_hits_triangle(r, through.origin, through.direction);
    hits_inside += segment_hits_triangle(r, inside.origin, inside.direction);
  }
  EXPECT_EQ(hits_through, 0);
  EXPECT_GE(hits_inside, 1);  // two where it meets a diagonal
}

TEST(MergeFlatRegions, KeepsARegionWithAHoleAFoldAndOneThatIsAlreadyTwoTriangles) {
  const auto ring = cells(0, 3, 0, 3, 0.0f, [](int i, int j) { return i == 1 && j == 1; });
  std::vector<Tri> folded = grid(2, 0.0f);
  for (Tri& t : folded)
    for (Vec3& p : t) p.z = p.x > 1.5f ? 1e-3f * (p.x - 1.5f) : 0.0f;  // bent by 0.06 degree
  const Hierarchy h = scene_of({ring, folded, grid(1, 5.0f)});
  EXPECT_FALSE(merge_flat_regions(h));
}

TEST(MergeFlatRegions, EveryBackendAnswersAsOnTheTessellatedSurfaces) {
  // A tessellated floor and an L-shaped shelf over it; segments between random points above,
  // between and below them, none grazing a seam closer than the rounding.
  const Hierarchy h = scene_of(
      {grid(12, 0.0f), cells(2, 8, 2, 8, 1.0f, [](int i, int j) { return i < 5 && j < 5; })});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> xy(-1.0f, 13.0f), z(-0.5f, 2.5f);
  std::vector<Segment> segments;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 a(xy(rng), xy(rng), z(rng)), b(xy(rng), xy(rng), z(rng));
    segments.push_back({a, b - a});
  }
  // The answer on the triangles as given, one by one.
  const std::vector<TriangleRecord> records = make_triangle_records(h);
  std::vector<uint8_t> expected(segments.size(), 0);
  for (size_t i = 0; i < segments.size(); ++i)
    for (const TriangleRecord& r : records)
      expected[i] |= segment_hits_triangle(r, segments[i].origin, segments[i].direction);
  for (BackendKind kind : {BackendKind::Embree, BackendKind::Grid, BackendKind::Brute}) {
    const auto backend = make_visibility_backend(kind, h);
    std::vector<uint8_t> out(segments.size(), 7);
    VisibilityStats stats;
    backend->occluded(segments, out, stats);
    size_t differ = 0;
    for (size_t i = 0; i < out.size(); ++i) differ += out[i] != expected[i];
    EXPECT_EQ(differ, 0u) << to_string(kind);
  }
}

}  // namespace
}  // namespace rad
