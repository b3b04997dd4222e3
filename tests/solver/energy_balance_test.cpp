// The energy bookkeeping: what a cluster shoots with overshooting, from its polygons' energies.
#include "solver/energy_balance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_builder.h"
#include "scenegen/scenegen.h"

namespace rad {
namespace {

TEST(ClusterUnshot, BeyondEveryBreakIsLinearInTheAmbientAsThePolygonsSum) {
  // A furnished room after a few shots with overshooting: clusters hold unshot energy of either
  // sign, and some of each within one cluster.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = testing::solve_shots(h, *vis, SolverOptions{}, 12);
  size_t linear = 0;
  for (size_t c = 0; c < s.scene.clusters.size(); ++c) {
    const ClusterUnshot& k = s.energy.cluster_unshot[c];
    // The per-polygon sum of what it would shoot at ambient a.
    auto shoots = [&](double a) {
      double e = 0.0;
      for (uint32_t j = s.scene.clusters.first[c]; j < s.scene.clusters.first[c + 1]; ++j) {
        const uint32_t p = s.scene.clusters.polygons[j];
        const UnshotEnergy& u = s.energy.unshot_energy[p];
        const double r =
            mean_component(s.solution.material_of(p).reflectance) * double(h.triangles.area[p]);
        e += std::abs(u.sum + r * a) + u.magnitude - std::abs(u.sum);
      }
      return e;
    };
    double magnitude = 0.0;
    for (uint32_t j = s.scene.clusters.first[c]; j < s.scene.clusters.first[c + 1]; ++j)
      magnitude += s.energy.unshot_energy[s.scene.clusters.polygons[j]].magnitude;
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
