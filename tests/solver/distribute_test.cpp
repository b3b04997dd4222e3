// The pieces of an MPI solve that need no MPI: how clusters are shared out, and unshot totals
// that do not depend on the order (or the split) of their terms. tests/app/mpi_test.sh runs the
// real thing under mpirun against the plain process.
#include "solver/distribute.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "scene_builder.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"

namespace rad {
namespace {

SolverState building_state(const Hierarchy& h) {
  SolverOptions o;
  return make_solver_state(h, o);
}

TEST(Distribute, EveryClusterHasOneOwnerAndTheVerticesAreBalanced) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::Building, 3000, 7));
  const SolverState s = building_state(h);
  for (int ranks : {1, 2, 3, 7}) {
    const std::vector<uint32_t> owner = assign_clusters(s.scene.clusters, s.solution.mesh, ranks);
    ASSERT_EQ(owner.size(), s.scene.clusters.size());
    std::vector<uint64_t> load(size_t(ranks), 0);
    uint64_t largest = 0;
    for (size_t c = 0; c < owner.size(); ++c) {
      ASSERT_LT(owner[c], uint32_t(ranks));
      uint64_t v = 0;
      for (uint32_t j = s.scene.clusters.first[c]; j < s.scene.clusters.first[c + 1]; ++j)
        v += s.solution.mesh.polygons[s.scene.clusters.polygons[j]].vertex_count();
      load[owner[c]] += v;
      largest = std::max(largest, v);
    }
    // Greedy to the least loaded: no two ranks differ by more than the largest cluster.
    const auto [lo, hi] = std::minmax_element(load.begin(), load.end());
    EXPECT_LE(*hi - *lo, largest) << ranks << " ranks";
    EXPECT_EQ(owner, assign_clusters(s.scene.clusters, s.solution.mesh, ranks))
        << "not deterministic";
  }
}

TEST(Distribute, NeighbouringClustersGoToDifferentRanks) {
  // A shot with a Lights list reaches a few rooms: their clusters must not all be one rank's.
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::Building, 3000, 7));
  const SolverState s = building_state(h);
  const std::vector<uint32_t> owner = assign_clusters(s.scene.clusters, s.solution.mesh, 2);
  size_t changes = 0;
  for (size_t c = 1; c < owner.size(); ++c) changes += owner[c] != owner[c - 1];
  EXPECT_GT(changes, owner.size() / 4);
}

TEST(UnshotTotals, AreTheSameBitsInAnyOrderOfThePolygons) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::Building, 3000, 7));
  SolverState s = building_state(h);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (UnshotEnergy& e : s.energy.unshot_energy) {
    e.sum = u(rng) * s.energy.emitted_energy * 1e-3 * u(rng) * u(rng);
    e.magnitude = std::abs(e.sum);
  }
  update_unshot_totals(s.energy, s.solution, s.scene.clusters, s.ownership.ranks);
  const double abs_total = s.energy.unshot_abs_total, signed_total = s.energy.unshot_signed_total;
  double plain = 0.0;
  for (const UnshotEnergy& e : s.energy.unshot_energy) plain += e.magnitude;
  EXPECT_NEAR(abs_total, plain, 1e-9 * plain);
  for (int k = 0; k < 5; ++k) {
    std::shuffle(s.energy.unshot_energy.begin(), s.energy.unshot_energy.end(), rng);
    update_unshot_totals(s.energy, s.solution, s.scene.clusters, s.ownership.ranks);
    EXPECT_EQ(s.energy.unshot_abs_total, abs_total);
    EXPECT_EQ(s.energy.unshot_signed_total, signed_total);
  }
}

}  // namespace
}  // namespace rad
