// One scene solved by several MPI ranks (solver/ranks.h): every rank holds the geometry and the
// shot log, and receives for its own clusters only. Per shot the ranks agree on the shooter by
// one reduction, its owner broadcasts the frozen source, every rank shoots and refines its own
// polygons, and the unshot totals are summed exactly. The answer does not depend on the number of
// ranks: the shots are the same, and every vertex's gathers are the same.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/ranks.h"
#include "solver/solver_state.h"

namespace rad {

/// What one rank did, for rank 0's statistics.
struct RankReport {
  SolverStats stats;
  double absorbed_energy = 0.0;
  double communication_seconds = 0.0;
  uint64_t broadcast_bytes = 0, broadcasts = 0;
  uint64_t vertices = 0;  // of its own polygons
};

/// The owner of every cluster among `ranks` ranks: clusters in index order, each to the rank
/// that holds the fewest initial-mesh vertices so far (ties: the lowest rank). Deterministic,
/// balanced by vertex count, and spread over the scene (neighbouring clusters go to different
/// ranks, so a shot that reaches one room still finds work on every rank).
std::vector<uint32_t> assign_clusters(const Clusters& clusters, const Mesh& mesh, int ranks);

/// Makes `s` this rank's share of the solve: sets s.ownership.ranks, s.ownership.cluster_owner and
/// s.ownership.owned, frees the meshes and zeroes the unshot energies of the polygons of other
/// ranks, and sums the unshot totals over the ranks. Collective. Throws rad::Error (on every rank)
/// when the ranks' states differ: another `identity` (the solve's fingerprint) or another number of
/// shots done.
void distribute(SolverState& s, Ranks& ranks, uint64_t identity);

/// Brings every polygon's mesh and unshot energy to rank 0, so its state is whole (as one
/// process would have it); returns every rank's report there, in rank order (empty elsewhere).
/// Collective.
std::vector<RankReport> collect(SolverState& s);

/// Frees again, on rank 0, the polygons of other ranks that collect() brought.
void release_foreign(SolverState& s);

/// The counters of all ranks, as one process would have counted them (times: rank 0's).
SolverStats total_stats(const std::vector<RankReport>& reports);
double total_absorbed(const std::vector<RankReport>& reports);

/// The owner's `src` on every rank (the others pass an empty one), a source of one of
/// `cluster_count` clusters. Collective.
void share_shot_source(Ranks& ranks, size_t cluster_count, ShotSource& src, uint32_t owner);

}  // namespace rad
