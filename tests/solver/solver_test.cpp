// The progressive solver's loop: which cluster shoots next. The loop as a whole is tested by
// analytic_scenes_test.cpp, determinism_test.cpp, checkpoint_test.cpp, clusters_test.cpp (energy
// balance of each `step`), edits_test.cpp and backend_agreement_test.cpp; goal_reached by
// tests/serve/session_test.cpp, to_string(StopReason) by tests/app/command_line_test.cpp.
#include "solver/solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "scene_builder.h"
#include "scenegen/scenegen.h"

namespace rad {
namespace {

double unshot_after(const Hierarchy& h, bool overshoot, int shots) {
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.overshoot = overshoot;
  return testing::solve_shots(h, *vis, o, shots).unshot_fraction();
}

TEST(Solver, OvershootingKeepsTheUnshotEnergyNearShootingWithout) {
  // Small clusters of many reflectances: each holds -rho x ambient after its shot. Chosen by what
  // they held, those went first and shot next to nothing, and the unshot energy grew (39% after
  // 40 shots here, against 23% without overshooting).
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const double plain = unshot_after(h, false, 40), over = unshot_after(h, true, 40);
  std::printf("unshot after 40 shots: %.4f without overshooting, %.4f with\n", plain, over);
  EXPECT_LE(over, 1.25 * plain) << "the overshoot held by the clusters grows";
}

TEST(Solver, AShooterWhoseShotsGatherAtMoreVerticesWaitsForMoreEnergy) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(step(s, *vis));
  // Each shot's cost is kept: the vertices of the polygons that received it.
  ASSERT_EQ(s.cluster_cost.size(), s.clusters.size());
  EXPECT_GT(s.cluster_cost[size_t(s.history.back().source)], 0.0);
  // Every cluster as costly: the most energy goes first.
  const std::vector<double> same(s.clusters.size(), 1000.0);
  s.cluster_cost = same;
  const std::optional<Shooter> most = choose_shooter(s);
  ASSERT_TRUE(most);
  // Another cluster that barely costs anything goes before it, with less energy.
  std::optional<Shooter> cheap;
  for (size_t c = 0; c < s.clusters.size() && !cheap; ++c) {
    if (int32_t(c) == most->cluster) continue;
    s.cluster_cost = same;
    s.cluster_cost[c] = 1.0;
    const std::optional<Shooter> x = choose_shooter(s);
    ASSERT_TRUE(x);
    if (x->cluster == int32_t(c)) cheap = x;
  }
  ASSERT_TRUE(cheap) << "no cheap cluster went first";
  EXPECT_LT(cheap->energy, most->energy);
  // The one with the most energy, its shots dear, waits.
  s.cluster_cost = same;
  s.cluster_cost[size_t(most->cluster)] = 1e12;
  const std::optional<Shooter> x = choose_shooter(s);
  ASSERT_TRUE(x);
  EXPECT_NE(x->cluster, most->cluster);
}

TEST(Solver, TheShooterHasTheMostEnergyPerCostOfAllClusters) {
  // choose_shooter passes over the clusters that cannot win by a bound on what they shoot: its
  // choice must be the one a look at every cluster makes, at every stage of a solve.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 2));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, {});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> cost(1.0, 5000.0);
  for (int shot = 0; shot < 60; ++shot) {
    if (shot % 5 == 0) {
      // Every cluster's cost known: it is expected at its cost plus the overhead of a shot.
      std::vector<double> costs(s.clusters.size());
      for (double& c : costs) c = std::floor(cost(rng));
      s.cluster_cost = costs;
      const double amb = ambient_estimate(s);
      int32_t best = -1;
      double most = 0.0;
      for (size_t c = 0; c < s.clusters.size(); ++c) {
        const double score = cluster_shooting_energy(s, c, amb) / (costs[c] + 1000.0);
        if (score > most) most = score, best = int32_t(c);
      }
      const std::optional<Shooter> chosen = choose_shooter(s);
      ASSERT_TRUE(chosen);
      EXPECT_EQ(chosen->cluster, best) << "after " << shot << " shots";
    }
    ASSERT_TRUE(step(s, *vis));
  }
}

TEST(Solver, ASolveWithoutEditsLogsItsMajorShotsOnly) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  const SolverState all = testing::solve_shots(h, *vis, o, 30);
  o.log_minor_shots = false;
  const SolverState major = testing::solve_shots(h, *vis, o, 30);
  EXPECT_EQ(all.shot_log.size(), 30u);
  ASSERT_LT(major.shot_log.size(), 30u);
  EXPECT_GT(major.shot_log.size(), 0u) << "the light's first shot is major";
  for (const ShotSource& src : major.shot_log) EXPECT_TRUE(src.major);
  // The same solve otherwise: the log is only read back by edits and forced subdivision.
  EXPECT_EQ(all.unshot_fraction(), major.unshot_fraction());
}

}  // namespace
}  // namespace rad
