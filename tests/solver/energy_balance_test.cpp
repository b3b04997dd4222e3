// The energy bookkeeping: what a cluster shoots with overshooting, from its polygons' energies.
#include "solver/energy_balance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_builder.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"

namespace rad {
namespace {

TEST(ClusterUnshot, WhatAClusterShootsIsItsPolygonsSumAtAnyAmbient) {
  // A furnished room after a few shots with overshooting: clusters hold unshot energy of either
  // sign, and some of each within one cluster; each channel is linear beyond its breaks.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = testing::solve_shots(h, *vis, SolverOptions{}, 12);
  size_t linear = 0;
  for (size_t c = 0; c < s.scene.clusters.size(); ++c) {
    const ClusterUnshot& k = s.energy.cluster_unshot[c];
    // The per-polygon sum of what it would shoot at ambient a.
    auto shoots = [&](const DVec3& a) {
      double e = 0.0;
      for (uint32_t j = s.scene.clusters.first[c]; j < s.scene.clusters.first[c + 1]; ++j) {
        const uint32_t p = s.scene.clusters.polygons[j];
        const DVec3 rho(s.solution.material_of(p).reflectance);
        const DVec3 u = s.energy.unshot_energy[p].channels;
        for (int ch = 0; ch < 3; ++ch)
          e += std::abs(u[ch] + rho[ch] * double(h.triangles.area[p]) * a[ch]) / 3.0;
      }
      return e;
    };
    // Without overshooting, the mean of the channels' absolute sums (what the choice reads).
    const double plain = mean_component(k.abs);
    EXPECT_NEAR(shoots(DVec3(0.0)), plain, 1e-12 * (1.0 + plain));
    if (!(k.lo.x <= k.hi.x)) continue;
    ++linear;
    const DVec3 scale = glm::max(DVec3(1.0), glm::max(glm::abs(k.lo), glm::abs(k.hi)));
    for (const DVec3& a : {k.hi, k.hi + 0.5 * scale, k.hi + 10.0 * scale, k.lo, k.lo - 0.5 * scale,
                           k.lo - 10.0 * scale, 0.5 * (k.lo + k.hi)}) {
      const double expected = shoots(a);
      EXPECT_NEAR(cluster_shooting_energy(s.energy, s.solution, s.scene.clusters, c, Vec3(a)),
                  expected, 1e-5 * (1.0 + expected));
    }
  }
  EXPECT_GT(linear, 10u);
}

TEST(ClusterUnshot, AClusterThatHasJustOvershotHoldsNothingToShoot) {
  // A coloured room, so the channels' ambients differ: right after a cluster's shot its unshot
  // radiosity is minus its reflectance times the ambient it shot, and what it would shoot at
  // that ambient is nothing. A grey estimate of the choice would see the difference between
  // its share and the channels', and could choose the cluster again and again for nothing.
  SceneDescription d = generate_scene(SceneKind::FurnishedRoom, 1000, 1);
  for (ObjectDescription& o : d.objects) o.material.reflectance *= Vec3(1.0f, 0.5f, 0.2f);
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  size_t checked = 0;
  for (int shot = 0; shot < 12; ++shot) {
    const std::optional<Shooter> chosen = choose_shooter(s);
    ASSERT_TRUE(chosen);
    const size_t c = size_t(chosen->cluster);
    const Vec3 a = ambient_estimate(s.energy) * float(retention(s.energy, c));
    ASSERT_TRUE(step(s, *vis));
    // Planar clusters receive nothing of their own shot; the ambient moved with the shot, so
    // the cluster's own unshot is compared with the ambient it shot at.
    if (!s.scene.clusters.planar.empty() && !s.scene.clusters.planar[c]) continue;
    if (mean_component(a) == 0.0f) continue;
    const double left = cluster_shooting_energy(s.energy, s.solution, s.scene.clusters, c, a);
    EXPECT_LE(left, 1e-5 * s.energy.emitted_energy) << "shot " << shot << ", cluster " << c;
    ++checked;
  }
  EXPECT_GT(checked, 3u);
}

}  // namespace
}  // namespace rad
