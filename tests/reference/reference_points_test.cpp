// Where reference points go, and the CSV files that hold them.
#include "reference/reference_points.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/error.h"
#include "scene/parser.h"

namespace rad {
namespace {

Hierarchy cornell() {
  return build_hierarchy(parse_scene_file(std::string(RAD_SOURCE_DIR) + "/scenes/cornell_box.des"));
}

TEST(ReferencePoints, AreaProportionalWithAMinimumPerTriangle) {
  const Hierarchy h = cornell();
  PointOptions o;
  const std::vector<uint32_t> n = points_per_triangle(h.triangles, o);
  ASSERT_EQ(n.size(), h.triangles.size());
  double area = 0.0;
  uint32_t total = 0;
  for (float a : h.triangles.area) area += a;
  for (size_t i = 0; i < n.size(); ++i) {
    EXPECT_GE(n[i], o.min_per_triangle);
    const double share = o.total * h.triangles.area[i] / area;
    if (share > o.min_per_triangle + 1) {
      EXPECT_NEAR(n[i], share, 1.0);
    }
    total += n[i];
  }
  EXPECT_GE(total, 1000u);
  EXPECT_LE(total, 2000u);
}

TEST(ReferencePoints, AFinelyTessellatedSceneGetsItsShareToo) {
  // The Cornell box cut 16 x 16: every triangle's share is below a half, yet the points must
  // cover the scene by area (rounding each share alone gave none).
  SceneDescription d = parse_scene_file(std::string(RAD_SOURCE_DIR) + "/scenes/cornell_box.des");
  for (ObjectDescription& o : d.objects) {
    std::vector<std::array<Vec3, 3>> fine;
    for (const auto& t : o.triangles) {
      for (int i = 0; i < 16; ++i) {
        for (int j = 0; i + j < 16; ++j) {
          auto at = [&](int a, int b) {
            return t[0] + (t[1] - t[0]) * (float(a) / 16) + (t[2] - t[0]) * (float(b) / 16);
          };
          fine.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
          if (i + j + 1 < 16) fine.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
      }
    }
    o.triangles = fine;
    o.triangle_locs.clear();
  }
  const Hierarchy h = build_hierarchy(d);
  PointOptions o;
  o.min_per_triangle = 0;
  const std::vector<uint32_t> n = points_per_triangle(h.triangles, o);
  uint32_t total = 0;
  for (uint32_t k : n) total += k;
  EXPECT_EQ(total, o.total);
  // Per Pure, the points follow the area.
  double area = 0.0;
  for (float a : h.triangles.area) area += a;
  for (const SceneObject& p : h.objects) {
    if (p.kind != ObjectKind::Pure) continue;
    double pa = 0.0;
    uint32_t pn = 0;
    for (uint32_t t = p.first_triangle; t < p.first_triangle + p.triangle_count; ++t) {
      pa += h.triangles.area[t], pn += n[t];
    }
    EXPECT_NEAR(pn, o.total * pa / area, 1.0) << p.name;
  }
}

TEST(ReferencePoints, LieInsideTheirTriangleAtTheirBarycentrics) {
  const Hierarchy h = cornell();
  PointOptions o;
  const std::vector<ReferencePoint> points = make_reference_points(h.triangles, o);
  for (const ReferencePoint& p : points) {
    const auto& c = h.triangles.corners[size_t(p.triangle)];
    EXPECT_GE(p.u, o.inset * 0.999f);
    EXPECT_GE(p.v, o.inset * 0.999f);
    EXPECT_GE(1.0f - p.u - p.v, o.inset * 0.99f);
    const Vec3 expected = c[0] + p.u * (c[1] - c[0]) + p.v * (c[2] - c[0]);
    EXPECT_LT(glm::length(p.position - expected), 1e-3f);
    EXPECT_EQ(p.normal, h.triangles.normal[size_t(p.triangle)]);
  }
}

TEST(ReferencePoints, AreStratified) {
  // A quarter of a triangle's points fall in each of the four sub-triangles cut at the edge
  // midpoints (give or take the strata they straddle).
  const Hierarchy h = cornell();
  PointOptions o;
  o.total = 4000;
  const std::vector<ReferencePoint> points = make_reference_points(h.triangles, o);
  std::vector<int> corner_a(h.triangles.size()), count(h.triangles.size());
  for (const ReferencePoint& p : points) {
    ++count[size_t(p.triangle)];
    if (p.u + p.v < 0.5f) ++corner_a[size_t(p.triangle)];
  }
  for (size_t t = 0; t < count.size(); ++t) {
    EXPECT_NEAR(corner_a[t], count[t] / 4.0, 2.0) << "triangle " << t;
  }
}

TEST(ReferencePoints, DeterministicForASeed) {
  const Hierarchy h = cornell();
  PointOptions o;
  const auto a = make_reference_points(h.triangles, o);
  const auto b = make_reference_points(h.triangles, o);
  o.seed = 2;
  const auto c = make_reference_points(h.triangles, o);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  size_t same_as_other_seed = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    same_as_other_seed += a[i].position == c[i].position;
  }
  EXPECT_EQ(same_as_other_seed, 0u);
}

TEST(ReferenceCsv, RoundTrips) {
  ReferenceSet set;
  set.comments = {"first line", "regenerate: something"};
  ReferencePoint p;
  p.triangle = 7;
  p.u = 0.123456789f;
  p.v = 0.5f;
  p.position = Vec3(552.8f, 0.001f, -3.0f);
  ReferenceValue v;
  v.radiosity = DVec3(53.40707, 1e-3, 0.0);
  v.standard_error = DVec3(0.0123, 4.5e-6, 0.0);
  set.points = {p, p};
  set.values = {v, v};
  std::stringstream s;
  write_reference_csv(s, set);
  const ReferenceSet back = read_reference_csv(s, "mem.csv");
  EXPECT_EQ(back.comments, set.comments);
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1].triangle, 7);
  EXPECT_EQ(back.points[1].u, p.u);
  EXPECT_EQ(back.points[1].position, p.position);
  EXPECT_NEAR(back.values[1].radiosity.x, v.radiosity.x, 1e-6 * v.radiosity.x);
  EXPECT_NEAR(back.values[1].standard_error.y, v.standard_error.y, 1e-3 * v.standard_error.y);
}

TEST(ReferenceCsv, ReportsTheLineOfABadRow) {
  std::stringstream s(
      "# c\ntriangle,u,v,x,y,z,B_r,B_g,B_b,stderr_r,stderr_g,stderr_b\n1,2,3,4,5,6,7,8,9,10,11\n");
  try {
    read_reference_csv(s, "bad.csv");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 3);
    EXPECT_EQ(e.loc().file, "bad.csv");
  }
}

}  // namespace
}  // namespace rad
