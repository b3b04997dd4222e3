// Per-object illuminance: a floor under one point light has I / h^2 at its foot, I h / r^3 at its
// corners, and the mean of that over its area.
#include "run/object_illuminance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

TEST(ObjectIlluminance, AFloorUnderAPointLightHasItsLeastMeanAndMost) {
  // A black 2 m x 2 m floor (no interreflection), 100 cd 1 m above its centre.
  SceneDescription d;
  ObjectDescription floor;
  floor.name = "floor";
  floor.material.reflectance = Vec3(0.0f);
  const Vec3 a(-1, 0, 1), b(1, 0, 1), c(1, 0, -1), e(-1, 0, -1);
  floor.triangles = {{a, b, c}, {a, c, e}};
  floor.triangle_locs.resize(2);
  d.roots.push_back(0);
  d.objects.push_back(floor);
  Hierarchy h = build_hierarchy(d);
  Light l;
  l.position = Vec3(0, 1, 0), l.intensity = 100.0f;
  h.lights.push_back(l);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  solve(s, *vis);
  const std::vector<ObjectIlluminance> objects = object_illuminance(s);
  ASSERT_EQ(objects.size(), 1u);
  const ObjectIlluminance& o = objects[0];
  EXPECT_EQ(o.name, "floor");
  EXPECT_NEAR(o.area, 4.0, 1e-5);
  EXPECT_NEAR(o.max, 100.0, 0.1);                        // at the foot: I / h^2
  EXPECT_NEAR(o.min, 100.0 / std::pow(3.0, 1.5), 0.02);  // a corner, r = sqrt(3)
  // The mean of I h / r^3 over the square, by the midpoint rule on a fine grid.
  double sum = 0.0;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = -1.0 + (i + 0.5) * 2.0 / n, z = -1.0 + (j + 0.5) * 2.0 / n;
      sum += 100.0 / std::pow(x * x + z * z + 1.0, 1.5);
    }
  }
  EXPECT_NEAR(o.mean, sum / (n * n), 0.01 * sum / (n * n));
  const std::string table = format_illuminance(objects, 12);
  EXPECT_NE(table.find("floor"), std::string::npos) << table;
}

}  // namespace
}  // namespace rad
