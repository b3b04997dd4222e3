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

// The generated furnished room's elements no smaller than 10 cm: the tests of this file look at
// which cluster shoots and what the books hold, not at the answer, and the coarser mesh runs
// them in a fraction of the time.
SolverOptions coarse() {
  SolverOptions o;
  o.min_size = 0.1f;
  return o;
}

double unshot_after(const Hierarchy& h, bool overshoot, int shots) {
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o = coarse();
  o.overshoot = overshoot;
  return testing::solve_shots(h, *vis, o, shots).energy.unshot_fraction();
}

TEST(Solver, OvershootingKeepsTheUnshotEnergyNearShootingWithout) {
  // Small clusters of many reflectances: each holds -rho x ambient after its shot. Chosen by what
  // they hold, those would go first and shoot next to nothing, and the unshot energy would stay
  // far above what shooting without overshooting leaves.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const double plain = unshot_after(h, false, 40), over = unshot_after(h, true, 40);
  std::printf("unshot after 40 shots: %.4f without overshooting, %.4f with\n", plain, over);
  EXPECT_LE(over, 1.25 * plain) << "the overshoot held by the clusters grows";
}

TEST(Solver, AShooterWhoseShotsGatherAtMoreVerticesWaitsForMoreEnergy) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, coarse());
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(step(s, *vis));
  // Each shot's cost is kept: the vertices of the polygons that received it.
  ASSERT_EQ(s.shots.cluster_cost.size(), s.scene.clusters.size());
  EXPECT_GT(s.shots.cluster_cost[size_t(s.shots.history.back().source)], 0.0);
  // Every cluster as costly: the most energy goes first.
  const std::vector<double> same(s.scene.clusters.size(), 1000.0);
  s.shots.cluster_cost = same;
  const std::optional<Shooter> most = choose_shooter(s);
  ASSERT_TRUE(most);
  // Another cluster that barely costs anything goes before it, with less energy.
  std::optional<Shooter> cheap;
  for (size_t c = 0; c < s.scene.clusters.size() && !cheap; ++c) {
    if (int32_t(c) == most->cluster) continue;
    s.shots.cluster_cost = same;
    s.shots.cluster_cost[c] = 1.0;
    const std::optional<Shooter> x = choose_shooter(s);
    ASSERT_TRUE(x);
    if (x->cluster == int32_t(c)) cheap = x;
  }
  ASSERT_TRUE(cheap) << "no cheap cluster went first";
  EXPECT_LT(cheap->energy, most->energy);
  // The one with the most energy, its shots dear, waits.
  s.shots.cluster_cost = same;
  s.shots.cluster_cost[size_t(most->cluster)] = 1e12;
  const std::optional<Shooter> x = choose_shooter(s);
  ASSERT_TRUE(x);
  EXPECT_NE(x->cluster, most->cluster);
}

TEST(Solver, TheShooterHasTheMostEnergyPerCostOfAllClusters) {
  // choose_shooter passes over the clusters that cannot win by a bound on what they shoot: its
  // choice must be the one a look at every cluster makes, at every stage of a solve.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 2));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, coarse());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> cost(1.0, 5000.0);
  for (int shot = 0; shot < 60; ++shot) {
    if (shot % 5 == 0) {
      // Every cluster's cost known: it is expected at its cost plus the overhead of a shot.
      std::vector<double> costs(s.scene.clusters.size());
      for (double& c : costs) c = std::floor(cost(rng));
      s.shots.cluster_cost = costs;
      const Vec3 amb = ambient_estimate(s.energy);
      int32_t best = -1;
      double most = 0.0;
      for (size_t c = 0; c < s.scene.clusters.size(); ++c) {
        const double score = cluster_shooting_energy(s.energy, s.solution, s.scene.clusters, c,
                                                     amb * float(retention(s.energy, c))) /
                             (costs[c] + 1000.0);
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
  SolverOptions o = coarse();
  const SolverState all = testing::solve_shots(h, *vis, o, 30);
  o.log_minor_shots = false;
  const SolverState major = testing::solve_shots(h, *vis, o, 30);
  EXPECT_EQ(all.shots.sources.size(), 30u);
  ASSERT_LT(major.shots.sources.size(), 30u);
  EXPECT_GT(major.shots.sources.size(), 0u) << "the light's first shot is major";
  for (const ShotSource& src : major.shots.sources) EXPECT_TRUE(src.major);
  // The same solve otherwise: the log is only read back by edits and forced subdivision.
  EXPECT_EQ(all.energy.unshot_fraction(), major.energy.unshot_fraction());
}

// Open scenes: light that leaves the scene is gone. Overshooting expects back only what a
// cluster's shots land (its retention); each of these solves must end on its own by
// convergence, with overshooting (the default) and without, in a few shots. max_shots only keeps
// a failure from running for ever.
struct OpenSolve {
  StopReason why;
  int64_t shots;
  double unshot;
  std::vector<double> retention;
};

OpenSolve solve_open(const SceneDescription& d, bool overshoot) {
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.overshoot = overshoot;
  o.max_shots = 2000;
  SolverState s = make_solver_state(h, o);
  const StopReason why = solve(s, *vis);
  std::vector<double> r;
  for (size_t c = 0; c < s.scene.clusters.size(); ++c) r.push_back(retention(s.energy, c));
  return {why, s.shots.count, s.energy.unshot_fraction(), r};
}

void expect_converges(const SceneDescription& d, int64_t most_shots) {
  for (const bool overshoot : {true, false}) {
    SCOPED_TRACE(overshoot ? "overshooting" : "without overshooting");
    const OpenSolve r = solve_open(d, overshoot);
    EXPECT_EQ(r.why, StopReason::Converged) << r.shots << " shots, unshot " << r.unshot;
    EXPECT_LE(r.shots, most_shots);
  }
}

// A triangle emitting 1 towards +z from z = z0, of reflectance rho.
void add_lamp(SceneDescription& d, float rho, float z0 = 0.0f) {
  testing::add_quad(d, "lamp", {0, 0, z0}, {1, 0, z0}, {1, 1, z0}, {0, 1, z0}, Vec3(rho), Vec3(1));
}

TEST(Solver, ALoneReflectingLampConverges) {
  // Overshooting sure of getting back rho x ambient made the lamp's own overshoot the next
  // ambient: at rho = 0.5 it shot +-1 of the emitted energy for ever, above 0.5 more each time.
  for (const float rho : {0.5f, 0.9f, 0.99f}) {
    SCOPED_TRACE(rho);
    SceneDescription d;
    add_lamp(d, rho);
    // Two triangles: each shoots its emission and then the overshoot it never gets back.
    expect_converges(d, 4);
    for (const double g : solve_open(d, true).retention)
      EXPECT_EQ(g, 0.0) << "nothing receives the lamp's light";
  }
}

TEST(Solver, ALampFacingAwayFromEverythingConverges) {
  SceneDescription d;
  add_lamp(d, 0.8f);
  // A floor below the lamp, facing it: the lamp's back, which shoots nothing.
  testing::add_quad(d, "floor", {-2, -2, -1}, {2, -2, -1}, {2, 2, -1}, {-2, 2, -1}, Vec3(0.8f),
                    Vec3(0));
  expect_converges(d, 4);
}

TEST(Solver, ALampOverASmallFloorInTheVoidConverges) {
  for (const float rho : {0.5f, 0.95f}) {
    SCOPED_TRACE(rho);
    SceneDescription d;
    // The lamp at z = 1 facing down, the floor at z = 0 facing up, both reflecting.
    testing::add_quad(d, "lamp", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Vec3(rho), Vec3(1));
    testing::add_quad(d, "floor", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Vec3(rho), Vec3(0));
    expect_converges(d, 20);
    // Each sees the other under a form factor of 0.2 (parallel unit squares a unit apart):
    // about that much of a shot lands.
    const OpenSolve r = solve_open(d, true);
    for (const double g : r.retention) {
      EXPECT_GT(g, 0.1);
      EXPECT_LT(g, 0.3);
    }
  }
}

TEST(Solver, AnOpenUmbraSceneConverges) {
  // A small lamp, a blocker under it and a floor, nothing around them.
  SceneDescription d;
  testing::add_quad(d, "lamp", {-0.2f, -0.2f, 2}, {-0.2f, 0.2f, 2}, {0.2f, 0.2f, 2},
                    {0.2f, -0.2f, 2}, Vec3(0.7f), Vec3(10));
  testing::add_quad(d, "blocker", {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                    {0.5f, -0.5f, 1}, Vec3(0.7f), Vec3(0));
  testing::add_quad(d, "blocker top", {-0.5f, -0.5f, 1.001f}, {0.5f, -0.5f, 1.001f},
                    {0.5f, 0.5f, 1.001f}, {-0.5f, 0.5f, 1.001f}, Vec3(0.7f), Vec3(0));
  testing::add_quad(d, "floor", {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Vec3(0.7f),
                    Vec3(0));
  expect_converges(d, 40);
}

TEST(Solver, ClosedSceneClustersKeepNearlyAllTheyShoot) {
  // Inside a closed box of emitting walls (nothing inside: the back of a lamp in it would take
  // light and keep none) every shot lands: retention about 1, so overshooting there is Cohen's
  // ambient as it was (the roulette's draw and rounding put it within a few percent).
  SceneDescription d;
  testing::add_closed_box(d, {0, 0, 0}, {1, 1, 1}, Vec3(0.5f), Vec3(1));
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  const double closed = s.energy.interreflection;
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(step(s, *vis));
  size_t shot = 0;
  for (size_t c = 0; c < s.scene.clusters.size(); ++c) {
    if (s.shots.cluster_cost.size() > c && s.shots.cluster_cost[c] > 0.0) {
      ++shot;
      EXPECT_GT(retention(s.energy, c), 0.95) << "cluster " << c;
    }
  }
  EXPECT_GE(shot, 3u);
  EXPECT_NEAR(s.energy.interreflection, closed, 0.1 * closed);
}

TEST(Solver, OvershootingKeepsAWeakChannelRight) {
  // A closed box of walls emitting (1, 1, 0.05), reflecting 0.7: every point's radiosity is
  // E / (1 - rho) in each channel. A grey ambient estimate (the channels' mean) overshoots the
  // blue channel by the others' share, and the solve ends with blue's unshot energy negative
  // and its radiosity off by several of its own percent.
  SceneDescription d;
  const Vec3 e(1.0f, 1.0f, 0.05f);
  const float rho = 0.7f;
  testing::add_closed_box(d, {0, 0, 0}, {1, 1, 1}, Vec3(rho), e);
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  ASSERT_TRUE(o.overshoot);
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  ASSERT_LE(s.energy.unshot_fraction(), o.converge);
  DVec3 sum(0.0);
  size_t n = 0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < s.solution.mesh.polygons[p].vertex_count(); ++v, ++n)
      sum += DVec3(s.solution.radiosity(p, v));
  }
  const DVec3 mean = sum / double(n), exact = DVec3(e) / (1.0 - double(rho));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean[c] / exact[c], 1.0, 0.005) << "channel " << c;
    EXPECT_GT(s.energy.unshot_channel_total[c], -1e-3 * s.energy.emitted_energy) << "channel " << c;
  }
}

TEST(Solver, RetentionLowersTheInterreflectionFactorAndIsRestoredExactly) {
  SceneDescription d;
  add_lamp(d, 0.5f);
  testing::add_quad(d, "floor", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Vec3(0.5f), Vec3(0));
  const Hierarchy h = build_hierarchy(d);
  SolverState s = make_solver_state(h, SolverOptions{});
  const double closed = s.energy.interreflection;
  EXPECT_DOUBLE_EQ(closed, 2.0) << "1 / (1 - 0.5)";
  for (size_t c = 0; c < s.scene.clusters.size(); ++c)
    set_retention(s.energy, s.solution, s.scene.clusters, c, 0.0);
  EXPECT_DOUBLE_EQ(s.energy.interreflection, 1.0) << "nothing lands: no interreflection";
  for (size_t c = 0; c < s.scene.clusters.size(); ++c)
    set_retention(s.energy, s.solution, s.scene.clusters, c, 1.0);
  EXPECT_EQ(s.energy.interreflection, closed);
  // Set in any order, recomputed from scratch (a checkpoint read, an edit): the same bits.
  for (size_t c = 0; c < s.scene.clusters.size(); ++c)
    set_retention(s.energy, s.solution, s.scene.clusters, c, 0.3 + 0.1 * double(c));
  const double some = s.energy.interreflection;
  for (size_t c = s.scene.clusters.size(); c-- > 0;)
    set_retention(s.energy, s.solution, s.scene.clusters, c, 0.7);
  for (size_t c = s.scene.clusters.size(); c-- > 0;)
    set_retention(s.energy, s.solution, s.scene.clusters, c, 0.3 + 0.1 * double(c));
  EXPECT_EQ(s.energy.interreflection, some);
  update_unshot_totals(s.energy, s.solution, s.scene.clusters, s.ownership.ranks);
  EXPECT_EQ(s.energy.interreflection, some);
}

}  // namespace
}  // namespace rad
