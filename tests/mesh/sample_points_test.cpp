#include "mesh/sample_points.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "mesh_fixtures.h"

namespace rad {
namespace {

TEST(SamplePoints, RegularGridHasMSquaredDistinctInteriorSamplesCentredOnTheCentroid) {
  for (int m = 1; m <= 6; ++m) {
    const auto s = regular_sample_barycentrics(m);
    ASSERT_EQ(s.size(), size_t(m * m));
    Vec3 mean(0.0f);
    std::set<std::pair<int, int>> distinct;
    for (const Vec3& w : s) {
      EXPECT_GT(w.x, 0.0f);
      EXPECT_GT(w.y, 0.0f);
      EXPECT_GT(w.z, 0.0f);
      EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f);
      mean += w;
      distinct.insert({int(std::lround(w.y * 3000)), int(std::lround(w.z * 3000))});
    }
    mean /= float(s.size());
    EXPECT_NEAR(mean.x, 1.0f / 3.0f, 1e-5f);
    EXPECT_NEAR(mean.y, 1.0f / 3.0f, 1e-5f);
    EXPECT_EQ(distinct.size(), s.size());
  }
}

TEST(SamplePoints, LocateLeafFindsTheLeafHoldingThePoint) {
  PolygonMesh p = testing::one_polygon({0, 0, 0}, {2, 0, 0}, {0.5f, 1.5f, 0});
  testing::split_randomly(p, 40, 7);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    float b = u(rng), c = u(rng);
    if (b + c > 1.0f) b = 1.0f - b, c = 1.0f - c;
    const Vec3 w(1.0f - b - c, b, c);
    Vec3 lw;
    const uint32_t e = locate_leaf(p, w, &lw);
    ASSERT_TRUE(p.elements[e].leaf());
    EXPECT_GE(lw.x, -1e-4f);
    EXPECT_GE(lw.y, -1e-4f);
    EXPECT_GE(lw.z, -1e-4f);
    const uint32_t* v = p.elements[e].v;
    const Vec3 q = p.positions[v[0]] * lw.x + p.positions[v[1]] * lw.y + p.positions[v[2]] * lw.z;
    const Vec3 expected = p.positions[0] * w.x + p.positions[1] * w.y + p.positions[2] * w.z;
    EXPECT_NEAR(glm::length(q - expected), 0.0f, 1e-4f);
  }
}

TEST(SamplePoints, InterpolationReproducesALinearField) {
  PolygonMesh p = testing::one_polygon();
  testing::split_randomly(p, 20, 11);
  std::vector<Vec3> field;
  for (const Vec3& q : p.positions) field.push_back(Vec3(2.0f * q.x + 1.0f, q.y, 0.5f));
  const Vec3 w(0.2f, 0.3f, 0.5f);
  const Vec3 x = p.positions[0] * w.x + p.positions[1] * w.y + p.positions[2] * w.z;
  const Vec3 got = interpolate_at(
      p, [&](uint32_t v) { return field[v]; }, w);
  EXPECT_NEAR(got.x, 2.0f * x.x + 1.0f, 1e-5f);
  EXPECT_NEAR(got.y, x.y, 1e-5f);
}

}  // namespace
}  // namespace rad
