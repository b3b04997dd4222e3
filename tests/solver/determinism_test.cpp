// Reproducibility: same radiosity whatever the thread count and the visibility backend.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

#include "scene/parser.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"

namespace rad {
namespace {

std::vector<Vec3> solve_cornell(BackendKind kind, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const Hierarchy h = build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box.des"));
  const auto vis = make_visibility_backend(kind, h);
  SolverOptions o;
  o.max_shots = 12;  // enough for the lights, the walls' first bounces and much subdivision
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  std::vector<Vec3> b;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < s.solution.mesh.polygons[p].vertex_count(); ++v)
      b.push_back(s.solution.radiosity(p, v));
  }
  return b;
}

TEST(Determinism, OneAndTwoThreadsGiveBitIdenticalRadiosity) {
  const auto one = solve_cornell(BackendKind::Embree, 1);
  const auto two = solve_cornell(BackendKind::Embree, 2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(Vec3)));
}

TEST(Determinism, OvershootingChoosesTheSameShootersWhateverTheThreadCount) {
  // With overshooting the shooter is found by a parallel reduction over the clusters: a room of
  // many small clusters, so it runs in many pieces.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 1000, 1));
  auto shooters = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    const auto vis = make_visibility_backend(BackendKind::Embree, h);
    SolverOptions o;
    o.overshoot = true;
    o.max_shots = 6;
    SolverState s = make_solver_state(h, o);
    solve(s, *vis);
    EXPECT_GT(s.scene.clusters.size(), 1000u);
    std::vector<int32_t> out;
    for (const ShotRecord& r : s.shots.history) out.push_back(r.source);
    return out;
  };
  EXPECT_EQ(shooters(1), shooters(2));
}

TEST(Determinism, GridAndEmbreeAgreeToOnePartInAHundredThousand) {
  const auto embree = solve_cornell(BackendKind::Embree, 2);
  const auto grid = solve_cornell(BackendKind::Grid, 2);
  ASSERT_EQ(embree.size(), grid.size()) << "different subdivision";
  // Backends agree when every vertex is within 1e-5 of the largest radiosity (docs/trust.md).
  // (A ray that passes within a micrometre of a block's edge may go either way in float; it
  // moves its vertex by a fraction of one sample's share.)
  float largest = 0, worst = 0;
  for (const Vec3& b : embree) largest = std::max(largest, max_component(b));
  for (size_t i = 0; i < embree.size(); ++i) {
    worst = std::max(worst, max_component(glm::abs(embree[i] - grid[i])) / largest);
  }
  std::printf("grid vs embree: %zu vertices, worst difference %.3g of the largest radiosity\n",
              embree.size(), worst);
  EXPECT_LE(worst, 1e-5f);
}

}  // namespace
}  // namespace rad
