// The solver state's own helpers: the scene's size the default limits scale with.
#include "solver/solver_state.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_builder.h"
#include "scenegen/scenegen.h"

namespace rad {
namespace {

Hierarchy box(float turn_y, float turn_x) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(2.0f, 1.0f, 3.0f), Vec3(0.5f), Vec3(1.0f));
  const float cy = std::cos(turn_y), sy = std::sin(turn_y), cx = std::cos(turn_x),
              sx = std::sin(turn_x);
  for (ObjectDescription& o : d.objects) {
    for (auto& t : o.triangles) {
      for (Vec3& p : t) {
        p = Vec3(cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z);
        p = Vec3(p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z) + Vec3(7.0f, -3.0f, 2.0f);
      }
    }
  }
  return build_hierarchy(d);
}

TEST(SceneSize, IsABoxsDiagonalHoweverTheBoxIsTurned) {
  const float diagonal = std::sqrt(4.0f + 1.0f + 9.0f);
  const Hierarchy straight = box(0.0f, 0.0f), turned = box(0.5236f, 0.3491f);
  EXPECT_NEAR(scene_size(straight), diagonal, 1e-5f * diagonal);
  EXPECT_NEAR(straight.bounds.diagonal(), diagonal, 1e-5f * diagonal);
  // For a box Ritter's first two passes find two opposite corners, whose sphere holds the rest:
  // the diagonal, to the rounding of the turn. The turned box's bounding box is far off.
  EXPECT_NEAR(scene_size(turned), diagonal, 1e-5f * diagonal);
  EXPECT_GT(turned.bounds.diagonal(), 1.2f * diagonal);
}

TEST(ClusterUnshot, BeyondEveryBreakIsLinearInTheAmbientAsThePolygonsSum) {
  // A furnished room after a few shots with overshooting: clusters hold unshot energy of either
  // sign, and some of each within one cluster.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = testing::solve_shots(h, *vis, SolverOptions{}, 12);
  size_t linear = 0;
  for (size_t c = 0; c < s.clusters.size(); ++c) {
    const ClusterUnshot& k = s.cluster_unshot[c];
    // The per-polygon sum of what it would shoot at ambient a.
    auto shoots = [&](double a) {
      double e = 0.0;
      for (uint32_t j = s.clusters.first[c]; j < s.clusters.first[c + 1]; ++j) {
        const uint32_t p = s.clusters.polygons[j];
        const UnshotEnergy& u = s.unshot_energy[p];
        const double r = mean_component(s.material_of(p).reflectance) * double(h.triangles.area[p]);
        e += std::abs(u.sum + r * a) + u.magnitude - std::abs(u.sum);
      }
      return e;
    };
    double magnitude = 0.0;
    for (uint32_t j = s.clusters.first[c]; j < s.clusters.first[c + 1]; ++j)
      magnitude += s.unshot_energy[s.clusters.polygons[j]].magnitude;
    EXPECT_DOUBLE_EQ(k.magnitude, magnitude);
    if (!(k.lo <= k.hi)) continue;
    ++linear;
    const double scale = std::max(1.0, std::max(std::abs(k.lo), std::abs(k.hi)));
    for (double a : {k.hi, k.hi + 0.5 * scale, k.hi + 10.0 * scale}) {
      EXPECT_NEAR(k.rest + k.sum + k.rho_area * a, shoots(a), 1e-9 * (1.0 + shoots(a)));
    }
    for (double a : {k.lo, k.lo - 0.5 * scale, k.lo - 10.0 * scale}) {
      EXPECT_NEAR(k.rest - (k.sum + k.rho_area * a), shoots(a), 1e-9 * (1.0 + shoots(a)));
    }
  }
  EXPECT_GT(linear, 10u);
}

}  // namespace
}  // namespace rad
