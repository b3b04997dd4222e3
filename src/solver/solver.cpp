#include "solver/solver.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <span>
#include <tuple>

#include "solver/distribute.h"
#include "solver/light_source.h"
#include "solver/refine.h"
#include "solver/shoot.h"

namespace rad {

namespace {

// What a shot costs besides gathering at its receivers' vertices (choosing it, freezing its
// source, culling), in vertices: a shot that reaches nothing is not free.
constexpr double kShotOverhead = 1000.0;

// Clusters by area, a bin per power of 2: alike in size, alike in what they see (a building's
// floors, its chairs' seats).
size_t area_bin(float area) {
  // frexp's exponent, read off the bits of a positive normal float (a pass over every cluster
  // each shot, of which the library call would take a tenth).
  const uint32_t biased = (std::bit_cast<uint32_t>(area) >> 23) & 0xffu;
  int e = int(biased) - 126;
  if (biased == 0 || biased == 0xffu || std::signbit(area)) std::frexp(double(area), &e);
  return size_t(std::clamp(e + 32, 0, 63));
}

// What a shot of each cluster is expected to cost, in vertices gathered: its last shot's, or
// for one not shot yet, the mean of the last shots of the clusters of its size shot so far (else
// of all clusters shot so far), and what every shot costs besides.
struct ExpectedCost {
  const SolverState& s;
  std::array<double, 64> bin_mean{};
  double mean = 0.0;

  explicit ExpectedCost(const SolverState& state) : s(state) {
    std::array<double, 64> sum{}, count{};
    for (size_t c = 0; c < s.shots.cluster_cost.size(); ++c) {
      if (!(s.shots.cluster_cost[c] > 0.0)) continue;
      const size_t b = area_bin(s.scene.clusters.area[c]);
      sum[b] += s.shots.cluster_cost[c], count[b] += 1.0;
    }
    double all = 0.0, shot = 0.0;
    for (size_t b = 0; b < 64; ++b) {
      bin_mean[b] = count[b] > 0.0 ? sum[b] / count[b] : 0.0;
      all += sum[b], shot += count[b];
    }
    mean = shot > 0.0 ? all / shot : 0.0;
  }

  double operator()(size_t c) const {
    double known = c < s.shots.cluster_cost.size() ? s.shots.cluster_cost[c] : 0.0;
    if (!(known > 0.0)) known = bin_mean[area_bin(s.scene.clusters.area[c])];
    if (!(known > 0.0)) known = mean;
    return known + kShotOverhead;
  }
};

}  // namespace

std::optional<Shooter> choose_shooter(const SolverState& s) {
  // The largest of the clusters' energies per cost, the energies kept current shot by shot for
  // the clusters a shot changed (ties: the lowest index). A shot without Lights lists changes
  // nearly every cluster, so a heap would be rebuilt each time: one parallel pass (over the
  // clusters' energies, or with overshooting over their polygons) costs less. Under MPI each
  // rank looks at its own clusters (the others' are 0), and one reduction picks among them.
  // Per cost: what a shot removes of the unshot energy is about its energy whatever it costs,
  // so the most energy per second goes first. A building's floor sees the rooms along
  // its doors and gathers at seven times the vertices of a chair's shot; it waits until it holds
  // seven times the energy, and shoots it in one go.
  // With overshooting a cluster shoots its unshot energy plus its share of the ambient: what
  // it would shoot now, not what it holds, says which goes first. (By what it holds, one that
  // holds the overshoot it shot last, -rho x ambient, shoots next and nothing again, and the
  // held overshoot of all of them grows: a furnished room ended with 42% of its energy unshot
  // after 900 shots.) Its share is what it expects back: the ambient times its retention.
  const bool overshoot = s.options.overshoot;
  const Vec3 amb = overshoot ? ambient_estimate(s.energy) : Vec3(0.0f);
  const ExpectedCost expected_cost(s);
  const Clusters& clusters = s.scene.clusters;
  // Mostly a pass over the clusters, not the polygons (ClusterUnshot).
  auto shooting = [&](size_t c) {
    return overshoot ? cluster_shooting_energy(s.energy, s.solution, clusters, c,
                                               amb * float(retention(s.energy, c)))
                     : mean_component(s.energy.cluster_unshot[c].abs);
  };
  using Best = std::pair<double, int32_t>;  // (score, -index): the larger wins, ties lowest
  const Best found = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, clusters.size(), 256), Best{0.0, 1},
      [&](const tbb::blocked_range<size_t>& r, Best b) {
        for (size_t c = r.begin(); c != r.end(); ++c) {
          if (!s.ownership.owns_cluster(c)) continue;
          const double cost = expected_cost(c);
          // What a cluster shoots is at most its magnitude plus its share of the ambient (each
          // polygon's |U + rho A a| <= |U| + rho A |a| per channel), with room for the sums'
          // rounding: one that cannot win even so is passed over without its polygons (the same
          // choice).
          if (overshoot) {
            const ClusterUnshot& u = s.energy.cluster_unshot[c];
            const double share =
                u.area * mean_component(u.rho * DVec3(glm::abs(amb))) * retention(s.energy, c);
            // The channels' absolute sums: the doubles cluster_shooting_energy adds.
            const double most = (mean_component(u.abs) + share) * (1.0 + 1e-9);
            if (Best{most / cost, -int32_t(c)} < b) continue;
          }
          const double e = shooting(c);
          if (!(e > 0.0)) continue;  // NaN too: it would win or lose by its index alone
          b = std::max(b, Best{e / cost, -int32_t(c)});
        }
        return b;
      },
      [](const Best& a, const Best& b) { return std::max(a, b); });
  double best_score = found.first;
  int32_t best = found.first > 0.0 ? -found.second : -1;
  if (s.ownership.ranks)
    std::tie(best_score, best) = s.ownership.ranks->max_location(best_score, best);
  if (best < 0 || !(best_score > 0.0)) return std::nullopt;
  // The owner freezes it (the others hold none of its unshot energy).
  return Shooter{best, s.ownership.owns_cluster(size_t(best)) ? shooting(size_t(best)) : 0.0};
}

namespace {

// Clears cluster c's unshot radiosity into the source of the next shot; `shot` is set to the
// energy it shoots (mean over the channels, signed).
ShotSource freeze_source(SolverState& s, size_t c, double energy, double& shot) {
  const Clusters& clusters = s.scene.clusters;
  // Overshooting (Feda, Purgathofer 1992): also shoot what the source will get back from the
  // ambient; its unshot radiosity becomes that much negative, shot later if still significant.
  // It gets back only as much as its shots land (retention): else a lamp alone in the void,
  // sure of getting back rho x ambient, is handed its own overshoot as the next ambient and
  // shoots +-1 of the emitted energy for ever. A cluster lies in one Pure: one reflectance.
  Vec3 over(0.0f);
  const bool overshoot = s.options.overshoot;
  if (overshoot) {
    over = s.solution.material_of(clusters.polygons[clusters.first[c]]).reflectance *
           ambient_estimate(s.energy) * float(retention(s.energy, c));
  }
  shot = 0.0;
  for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j)
    shot += s.energy.unshot_energy[clusters.polygons[j]].sum;
  auto set_unshot = [&](const Vec3& add, bool assign) {
    for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j) {
      for (VertexState& v : s.solution.vertex_states[clusters.polygons[j]]) {
        v.unshot = assign ? add : v.unshot + add;
      }
    }
  };
  if (overshoot) set_unshot(over, false);
  ShotSource src = make_shot_source(s, int32_t(c));
  set_unshot(-over, true);
  // Each light group's share goes with the source (light groups never overshoot).
  assert(!overshoot || s.solution.group_count == 0);
  if (s.solution.group_count > 0) {
    for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j) {
      for (VertexState& v : s.solution.group_states[clusters.polygons[j]]) v.unshot = Vec3(0.0f);
    }
  }
  std::vector<UnshotEnergy> left;
  for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j) {
    left.push_back(overshoot ? polygon_unshot_energy(s.solution, clusters.polygons[j])
                             : UnshotEnergy{});
  }
  set_unshot_energies(s.energy, s.solution, s.scene.clusters,
                      {clusters.polygons.data() + clusters.first[c], left.size()}, left);
  for (const UnshotEnergy& e : left) shot -= e.sum;

  src.major = is_major_shot(s, energy);
  // A major shot lights every receiver it may: its part is gathered again at new vertices and
  // holds the sharp shadows.
  if (!src.major)
    aim_roulette(src, s.options.roulette * s.energy.radiosity_scale, s.shots.count + 1);
  return src;
}

// Adds the shot cluster c just made to its balance and sets its retention: what its receivers
// gained (absorbed plus unshot, `absorbed` and `unshot` against the unshot energies they held)
// against what it shot, `shot` signed and `magnitude` as chosen (each the owner's figure, 0 on
// other ranks). Summed exactly and added in shot order: every rank sets the same bits.
void measure_retention(SolverState& s, size_t c, double shot, double magnitude,
                       std::span<const uint32_t> receivers, std::span<const double> absorbed,
                       std::span<const UnshotEnergy> unshot) {
  std::vector<double> landed(receivers.size());
  for (size_t i = 0; i < receivers.size(); ++i)
    landed[i] = absorbed[i] + (unshot[i].sum - s.energy.unshot_energy[receivers[i]].sum);
  const double mine[2] = {shot, magnitude};
  const std::span<const double> terms[3] = {landed, {mine, 1}, {mine + 1, 1}};
  double sums[3];
  exact_energy_sums(s.energy, s.ownership.ranks, terms, sums);
  // Channels of opposite signs (after an edit) leave a signed energy that says little of what
  // was shot: the last retention stands.
  if (!(std::abs(sums[1]) >= 0.5 * sums[2] && sums[2] > 0.0)) return;
  if (s.energy.cluster_balance.size() < s.scene.clusters.size())
    s.energy.cluster_balance.resize(s.scene.clusters.size());
  ShotBalance& b = s.energy.cluster_balance[c];
  b.shot += std::abs(sums[1]);
  b.landed += sums[1] > 0.0 ? sums[0] : -sums[0];
  set_retention(s.energy, s.solution, s.scene.clusters, c, b.retention());
}

}  // namespace

void find_buried_vertices_once(const SolverOptions& options, const Solution& sol,
                               SceneCaches& scene, SolverStats& stats,
                               const VisibilityBackend& vis) {
  // Without shadows nothing blocks a buried vertex's view, and it gathers where it is.
  if (!scene.buried.found) {
    if (options.shadows) {
      scene.buried = find_all_buried_vertices(sol.hierarchy->triangles, sol.mesh, vis,
                                              buried_probe(scene), stats.rays);
    } else {
      scene.buried.moved.assign(sol.mesh.polygons.size(), {});
      scene.buried.covered.assign(sol.mesh.polygons.size(), {});
      scene.buried.found = true;
    }
  }
}

std::optional<ShotRecord> step(SolverState& s, const VisibilityBackend& vis) {
  const auto t0 = std::chrono::steady_clock::now();
  find_buried_vertices_once(s.options, s.solution, s.scene, s.stats, vis);
  // The lights shoot first, in order, each once (every rank knows them: nothing to share);
  // then the cluster chosen.
  ShotSource src;
  std::optional<Shooter> shooter;
  double shot = 0.0;  // the cluster's energy, signed (the owner's figure; 0 on the other ranks)
  const auto light = std::find_if(s.energy.light_unshot.begin(), s.energy.light_unshot.end(),
                                  [](const Vec3& u) { return u != Vec3(0.0f); });
  if (light != s.energy.light_unshot.end()) {
    const int32_t i = int32_t(light - s.energy.light_unshot.begin());
    src = make_light_source(s.scene.shooting_lights, i, *light, s.solution.hierarchy->bounds);
    if (s.solution.group_count > 0) src.light_group = int32_t(s.solution.light_group[size_t(i)]);
    *light = Vec3(0.0f);
  } else {
    shooter = choose_shooter(s);
    if (!shooter) return std::nullopt;
    const size_t c = size_t(shooter->cluster);
    // The cluster's owner freezes it as the source (the one rank that holds its radiosity) and
    // shares it with the other ranks.
    if (s.ownership.owns_cluster(c)) src = freeze_source(s, c, shooter->energy, shot);
    if (s.ownership.ranks) {
      share_shot_source(*s.ownership.ranks, s.scene.clusters.size(), src,
                        s.ownership.cluster_owner[c]);
    }
  }
  const bool major = src.major;
  const ShotContext shot_parts{s.options,  s.scene,     s.energy, s.shots, s.ownership,
                               s.solution, s.receivers, s.kept,   s.stats};
  const std::vector<uint32_t>& receivers = shoot_to_receivers(shot_parts, src, vis, major).polygons;
  const auto t1 = std::chrono::steady_clock::now();

  // Bookkeeping per received polygon: the energy it absorbed and the energy it holds unshot,
  // summed in index order so the result does not depend on the thread count. One look at each
  // receiver also says whether it needs refining (most of a large scene's do not); those
  // refined are counted again after.
  std::vector<double> absorbed(receivers.size(), 0.0);
  std::vector<UnshotEnergy> unshot(receivers.size());
  std::vector<uint8_t> refining(receivers.size(), 0);
  auto count = [&](size_t i) {
    const PolygonEnergies e = polygon_energies(s.solution, receivers[i]);
    absorbed[i] = e.absorbed;
    unshot[i] = e.unshot;
  };
  tbb::parallel_for(size_t(0), receivers.size(), [&](size_t i) {
    // A receiver that gained nothing (every ray blocked: most of those behind a building's
    // walls that culling could not prove hidden) holds what it held and needs no more refining
    // than after its last change, unless the middle of one of its leaves gained
    // (Receivers::bright_middles).
    const std::vector<VertexState>& vs = s.solution.vertex_states[receivers[i]];
    if (s.receivers.bright_middles_of(receivers[i]).empty() &&
        std::all_of(vs.begin(), vs.end(),
                    [](const VertexState& v) { return v.last_gain == Vec3(0.0f); })) {
      unshot[i] = s.energy.unshot_energy[receivers[i]];
      return;
    }
    count(i);
    refining[i] = needs_refinement(s.options, s.energy, s.scene, s.solution, receivers[i], major,
                                   s.receivers.bright_middles_of(receivers[i]));
  });
  std::vector<uint32_t> refined, to_refine;
  for (size_t i = 0; i < receivers.size(); ++i) {
    if (refining[i]) refined.push_back(uint32_t(i)), to_refine.push_back(receivers[i]);
  }
  refine_after_shot({s.options, s.energy, s.shots, s.solution, s.scene, s.stats}, s.receivers, src,
                    vis, major, to_refine);
  if (src.major || s.options.log_minor_shots) s.shots.sources.push_back(std::move(src));
  tbb::parallel_for(size_t(0), refined.size(), [&](size_t j) { count(refined[j]); });
  if (shooter) {
    const size_t c = size_t(shooter->cluster);
    measure_retention(s, c, shot, s.ownership.owns_cluster(c) ? shooter->energy : 0.0, receivers,
                      absorbed, unshot);
  }
  for (double a : absorbed) s.energy.absorbed_energy += a;
  // The totals and the clusters' energies follow the polygons the shot changed, not the scene.
  set_unshot_energies(s.energy, s.solution, s.scene.clusters, receivers, unshot);
  share_unshot_totals(s.energy, s.ownership.ranks);
  const auto t2 = std::chrono::steady_clock::now();
  s.stats.shoot_seconds += std::chrono::duration<double>(t1 - t0).count();
  s.stats.refine_seconds += std::chrono::duration<double>(t2 - t1).count();

  // What this shot cost, for the next choice of shooter (over the ranks: the same on each).
  if (shooter) {
    int64_t gathered = 0;
    for (uint32_t p : receivers) gathered += int64_t(s.solution.vertex_states[p].size());
    if (s.ownership.ranks) s.ownership.ranks->sum(std::span<int64_t>(&gathered, 1));
    s.shots.cluster_cost.resize(s.scene.clusters.size(), 0.0);
    s.shots.cluster_cost[size_t(shooter->cluster)] = double(gathered);
  }

  ++s.shots.count;
  ShotRecord r{s.shots.count, shooter ? shooter->cluster : -1 - src.light,
               s.stats.shoot_seconds + s.stats.refine_seconds, s.energy.unshot_fraction()};
  s.shots.history.push_back(r);
  return r;
}

const char* to_string(StopReason r) {
  switch (r) {
    case StopReason::Converged:
      return "converged";
    case StopReason::MaxShots:
      return "shot limit reached";
    case StopReason::TimeLimit:
      return "time limit reached";
    case StopReason::NothingToShoot:
      return "nothing left to shoot";
    case StopReason::Interrupted:
      return "interrupted";
    case StopReason::MemoryLimit:
      return "memory limit reached";
  }
  return "?";
}

std::optional<StopReason> goal_reached(const SolverState& s) {
  if (s.energy.unshot_fraction() <= s.options.converge) return StopReason::Converged;
  if (s.options.max_shots >= 0 && s.shots.count >= s.options.max_shots) return StopReason::MaxShots;
  return std::nullopt;
}

StopReason solve(SolverState& s, const VisibilityBackend& vis,
                 const std::function<void(const SolverState&, const ShotRecord&)>& on_shot,
                 const std::function<std::optional<StopReason>()>& stop) {
  const auto start = std::chrono::steady_clock::now();
  const SolverOptions& o = s.options;
  for (;;) {
    if (const std::optional<StopReason> goal = goal_reached(s)) return *goal;
    std::optional<StopReason> why = stop ? stop() : std::nullopt;
    if (!why && o.time_limit > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
            o.time_limit) {
      why = StopReason::TimeLimit;
    }
    // The ranks stop together: any rank's reason (a signal, its clock, its memory) stops all.
    if (s.ownership.ranks) {
      const int64_t agreed = s.ownership.ranks->max(why ? int64_t(*why) + 1 : 0);
      why = agreed > 0 ? std::optional(StopReason(agreed - 1)) : std::nullopt;
    }
    if (why) return *why;
    const std::optional<ShotRecord> r = step(s, vis);
    if (!r) return StopReason::NothingToShoot;
    if (on_shot) on_shot(s, *r);
  }
}

}  // namespace rad
