#include "solver/distribute.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <type_traits>

#include "core/error.h"
#include "solver/state_codec.h"
#include "solver/texture_factors.h"

namespace rad {

std::vector<uint32_t> assign_clusters(const Clusters& clusters, const Mesh& mesh, int ranks) {
  assert(ranks >= 1);
  std::vector<uint64_t> load(size_t(ranks), 0);
  std::vector<uint32_t> owner(clusters.size(), 0);
  for (size_t c = 0; c < clusters.size(); ++c) {
    size_t least = 0;
    for (size_t r = 1; r < load.size(); ++r) least = load[r] < load[least] ? r : least;
    owner[c] = uint32_t(least);
    for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j)
      load[least] += mesh.polygons[clusters.polygons[j]].vertex_count();
  }
  return owner;
}

void distribute(SolverState& s, Ranks& ranks, uint64_t identity) {
  // Every rank must start from the same state: a scene or a checkpoint that one node sees
  // differently would make the ranks shoot different shots and wait on each other for ever.
  auto same = [&](int64_t v) { return ranks.max(v) == -ranks.max(-v); };
  if (!same(int64_t(identity >> 2)) || !same(s.shots.count)) {
    throw Error(
        "the ranks do not hold the same solve: the scene, the options or the checkpoint differ "
        "between them (is every file the same on every node?)");
  }
  s.ownership.ranks = &ranks;
  s.ownership.cluster_owner = assign_clusters(s.scene.clusters, s.solution.mesh, ranks.size());
  s.ownership.owned.assign(s.solution.mesh.polygons.size(), 0);
  const Clusters& clusters = s.scene.clusters;
  for (size_t c = 0; c < clusters.size(); ++c) {
    if (s.ownership.cluster_owner[c] != uint32_t(ranks.rank())) continue;
    for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j)
      s.ownership.owned[clusters.polygons[j]] = 1;
  }
  release_foreign(s);
  if (ranks.rank() != 0) {  // rank 0 keeps the counters a resumed checkpoint brought
    s.stats = SolverStats{};
    s.energy.absorbed_energy = 0.0;
  }
  update_unshot_totals(s.energy, s.solution, s.scene.clusters, s.ownership.ranks);
}

void release_foreign(SolverState& s) {
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    if (s.ownership.owns(p)) continue;
    s.solution.mesh.polygons[p] = PolygonMesh{};
    std::vector<VertexState>().swap(s.solution.vertex_states[p]);
    if (!s.solution.group_states.empty())
      std::vector<VertexState>().swap(s.solution.group_states[p]);
    std::vector<VertexCopy>().swap(s.scene.shared.copies[p]);
    s.energy.unshot_energy[p] = UnshotEnergy{};
  }
}

std::vector<RankReport> collect(SolverState& s) {
  static_assert(std::is_trivially_copyable_v<RankReport>);
  assert(s.ownership.ranks);
  Ranks& ranks = *s.ownership.ranks;
  RankReport mine;
  mine.stats = s.stats;
  mine.absorbed_energy = s.energy.absorbed_energy;
  mine.communication_seconds = ranks.communication_seconds;
  mine.broadcast_bytes = ranks.broadcast_bytes;
  mine.broadcasts = ranks.broadcasts;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p)
    if (s.ownership.owns(p)) mine.vertices += s.solution.mesh.polygons[p].vertex_count();
  ByteWriter w;
  w.pod(mine);
  if (ranks.rank() != 0) {
    for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
      if (!s.ownership.owns(p)) continue;
      w.pod(uint32_t(p));
      write_polygon(w, s.solution.mesh.polygons[p], s.solution.vertex_states[p],
                    s.solution.group_states_of(p), s.solution.texture_factors[p],
                    s.scene.shared.copies[p]);
      w.pod(s.energy.unshot_energy[p]);
      // Where its buried vertices gather: what rank 0 renders and solves light groups with.
      w.vec(p < s.scene.buried.moved.size() ? s.scene.buried.moved[p] : std::vector<MovedVertex>{});
    }
  }
  // Every polygon of every rank must come: count them as they arrive.
  std::vector<uint64_t> expected(size_t(ranks.size()), 0), received(size_t(ranks.size()), 0);
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p)
    ++expected[s.ownership.cluster_owner[s.scene.clusters.cluster_of[p]]];
  std::vector<RankReport> reports;
  ranks.gather(std::move(w.out), [&](int r, std::string& part) {
    ByteReader in(part, 0, fmt::format("rank {}", r), "message between ranks");
    reports.push_back(in.pod<RankReport>());
    while (r > 0 && !in.done()) {
      const auto p = in.pod<uint32_t>();
      if (p >= s.solution.mesh.polygons.size() ||
          s.ownership.cluster_owner[s.scene.clusters.cluster_of[p]] != uint32_t(r))
        in.fail(fmt::format("polygon {} is not the rank's", p));
      std::vector<VertexState> group_states;
      read_polygon(in, s.solution.mesh.polygons[p], s.solution.vertex_states[p], group_states,
                   s.solution.texture_factors[p], s.scene.shared.copies[p],
                   s.solution.mesh.polygons.size(),
                   is_textured(s.solution.hierarchy->triangles, p, s.solution.object_of(p)),
                   s.solution.group_count);
      if (s.solution.group_count > 0) s.solution.group_states[p] = std::move(group_states);
      s.energy.unshot_energy[p] = in.pod<UnshotEnergy>();
      std::vector<MovedVertex> moved;
      in.vec(moved);
      if (!moved.empty() || p < s.scene.buried.moved.size()) {
        s.scene.buried.moved.resize(
            std::max(s.scene.buried.moved.size(), s.solution.mesh.polygons.size()));
        // Covered vertices only steer refinement, which rank 0 does not do for these polygons
        // after the solve: their lists are not sent, only sized.
        s.scene.buried.covered.resize(s.scene.buried.moved.size());
        s.scene.buried.moved[p] = std::move(moved);
      }
      ++received[size_t(r)];
    }
    if (r > 0 && received[size_t(r)] != expected[size_t(r)])
      in.fail(fmt::format("{} of its {} polygons", received[size_t(r)], expected[size_t(r)]));
    std::string().swap(part);  // decoded: free it before the next rank's arrives
  });
  return reports;
}

SolverStats total_stats(const std::vector<RankReport>& reports) {
  SolverStats t;
  for (const RankReport& r : reports) t += r.stats;
  // Times are rank 0's wall clock (the ranks shoot at once); each rank's are in its report.
  if (!reports.empty()) {
    t.shoot_seconds = reports[0].stats.shoot_seconds;
    t.refine_seconds = reports[0].stats.refine_seconds;
  }
  return t;
}

double total_absorbed(const std::vector<RankReport>& reports) {
  double t = 0.0;
  for (const RankReport& r : reports) t += r.absorbed_energy;
  return t;
}

void share_shot_source(Ranks& ranks, size_t cluster_count, ShotSource& src, uint32_t owner) {
  ByteWriter w;
  if (uint32_t(ranks.rank()) == owner) write_shot(w, src);
  ranks.broadcast(w.out, int(owner));
  if (uint32_t(ranks.rank()) == owner) return;
  ByteReader in(w.out, 0, fmt::format("rank {}", owner), "message between ranks");
  src = read_shot(in, cluster_count, {}, {});  // lights are never shared: every rank shoots them
}

}  // namespace rad
