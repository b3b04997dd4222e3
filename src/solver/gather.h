// What one receiving point gathers from one shooting source (design §4, EQ 7).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "solver/kept_rays.h"
#include "solver/shot_source.h"
#include "solver/solver_state.h"

namespace rad {

/// Per-thread buffers and counters for gathering; reused across vertices (no allocation in
/// the loop once sized).
struct GatherScratch {
  std::vector<float> end_x, end_y, end_z;  // far ends of the shadow fan
  std::vector<uint8_t> blocked;
  std::vector<float> weight;  // coarse samples' kernels
  std::vector<uint32_t> active;
  std::vector<uint32_t> unknown;      // active samples (indices into `active`) with no kept answer
  std::vector<float> coarse_visible;  // near field: visible part of each coarse sample
  std::vector<float> round_ends;      // a penumbra round's ends (draw_ray_ends)
  std::vector<float> draw_weight;     // penumbra rounds: each fine sample's part of the gain
  std::vector<float> clear;           // per active sample, the part of its rays not blocked
  std::vector<Vec3> group_gain;       // with light groups: each group's part of a gain
  std::vector<Vec3> group_all, group_major;  // regather_shots' sums per group (refine.h)
  std::vector<float> fine_weight;            // fine samples' weights (x visibility, once traced)
  std::vector<float> stratum_weight;         // near field: each stratum's fine samples' weight
  std::vector<uint32_t> edge_lane;           // near field: each stratum's heaviest fine sample
  SolverStats stats;
};

/// Each light group's part of a point's gain (gather_from_source), in `scratch`'s buffer sized
/// for `groups` of them: empty without groups.
inline std::span<Vec3> group_gains(GatherScratch& scratch, size_t groups) {
  scratch.group_gain.resize(groups);
  return scratch.group_gain;
}

struct GatherSettings {
  FormFactorMethod method = FormFactorMethod::Analytic;
  bool shadows = true;
  float cut = 0.0f;  // absolute intensity-cut level (radiosity units)
  float shadow_offset = 0.0f;
  float inset = kGatherInset;  // fraction of the way to the polygon centroid a point moves
  /// Penumbra rounds (SolverOptions::penumbra_rays): where a point's rays to a shot's
  /// samples (or to its corners) disagree, this many more rays per sample, each round to other
  /// points of the strata drawn by a hash of the point, and the visibility of each sample their
  /// mean; where they all agree the source is hidden, the first two rounds probe for gaps and
  /// the rest follow where a probe finds the source.
  uint32_t penumbra_rays = 0;
  /// Rounds only for shots whose mean sample carries at least this energy (area x mean-channel
  /// radiosity).
  double penumbra_sample_energy = 0.0;
  /// Rounds for every source with fine points, major or not, whatever it carries: a picture's
  /// pixels (gathered_image.h), where every penumbra shows at the pixel and no answer is kept.
  bool penumbra_every_source = false;
};

/// Where x lies against every triangle of the source, conservatively: +1 in front of all, -1
/// behind all (or on their plane), 0 unknown (a curved source seen from near its surface).
int receiver_side(const ShotSource& src, const Vec3& x);

/// The irradiance-like gain H (radiosity before the receiver's reflectance) that the point `x`
/// with unit normal `n` on a receiving polygon whose centroid is `centroid` gets from `src`.
/// x is first moved a tiny fraction towards the centroid, so a vertex on the line where two
/// polygons meet is evaluated inside its own polygon, where the neighbour is not edge-on.
/// With `kept`, the shadow rays whose answers it holds are not traced again, and the answers
/// of those traced are kept in it (kept_rays.h); the result is the same. With light groups,
/// `groups` (one per group, as many as the source's ShotSource::groups, or for a light the
/// solution's group count) gets each group's part of the gain, the same weights and visibility
/// applied to its share: they add up to the result. Thread-safe given a per-thread scratch (and
/// a record of kept answers no other thread uses).
Vec3 gather_from_source(const Vec3& x, const Vec3& n, const Vec3& centroid, const ShotSource& src,
                        const VisibilityBackend& vis, const GatherSettings& settings,
                        GatherScratch& scratch, const VertexRays* kept = nullptr,
                        std::span<Vec3> groups = {});

/// The frame of every parallel gathering loop: body(begin, end, scratch) over [0, n) in chunks
/// of about `grain`, each chunk on one thread with denormals flushed (core/denormals.h) and that
/// thread's scratch; then every thread's counters are added to `stats`. One call per chunk, none
/// per vertex or ray.
void parallel_gather(size_t n, size_t grain, SolverStats& stats,
                     const std::function<void(size_t, size_t, GatherScratch&)>& body);

}  // namespace rad
