// A shooting cluster frozen for one shot: its geometry and its samples' unshot radiosity.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/aabb.h"
#include "core/math.h"
#include "core/position_bits.h"
#include "scene/light.h"

namespace rad {

struct SolverState;

/// Points on a source, each with the normal and the area it stands for, and the unshot
/// radiosity there, as a structure of arrays padded to whole groups of kLanes so the kernel loops
/// over them run as fixed-width vector code.
struct SampleLanes {
  static constexpr size_t kLanes = 8;
  std::vector<float> x, y, z;               // position
  std::vector<float> nx, ny, nz;            // unit normal of the surface there
  std::vector<float> area;                  // area the sample stands for; 0 for padding
  std::vector<float> r, g, b;               // unshot radiosity
  size_t size() const { return x.size(); }  // including padding
  bool empty() const { return x.empty(); }
  void push_back(const Vec3& p, const Vec3& n, float a, const Vec3& u);
  /// Appends dead lanes (area 0) up to the next multiple of kLanes.
  void pad();
  Vec3 point(size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 normal(size_t i) const { return {nx[i], ny[i], nz[i]}; }
  Vec3 value(size_t i) const { return {r[i], g[i], b[i]}; }
};

/// With light groups (light_groups.h): one group's part of what a source shoots, per lane of
/// its `sample` and of its `fine_sample` (whose points they share), and its mean. The groups'
/// values add up to the source's.
struct GroupShare {
  std::vector<float> r, g, b;
  std::vector<float> fine_r, fine_g, fine_b;
  Vec3 mean_unshot{0.0f};
};

/// A cluster (solver/clusters.h) frozen as the source of one shot: its outline, its samples and
/// their unshot radiosity. Or a light of the scene (light >= 0, cluster -1): a point, spot or
/// directional light (scene/light.h), whose gain at a point is its illuminance there
/// (light_source.h).
struct ShotSource {
  int32_t cluster = -1;
  // The light that shoots (its index in Hierarchy::lights), what it shoots per channel (its
  // colour, or an edit's change of it: the gain is that times its illuminance), the light
  // itself, and for the sun the directions toward points of its disc, spread by area, and how
  // far its shadow rays go (past the scene's bounds).
  int32_t light = -1;
  int32_t light_group = -1;  // with light groups: the light's group
  Vec3 light_colour{0.0f};
  const Light* emitter = nullptr;
  std::vector<Vec3> sun_directions;
  float sun_reach = 0.0f;
  bool planar = true;  // a planar cluster: its own polygons cannot receive from it
  // Where receivers stand against the source's triangles (see receiver_side in gather.h).
  Vec3 centroid{0.0f}, axis{0.0f};
  float cone_cos = 1.0f, cone_sin = 0.0f, offset_lo = 0.0f, offset_hi = 0.0f;
  Aabb box;
  float area = 0.0f;
  float extent = 0.0f;               // box diagonal
  std::vector<Vec3> edge_a, edge_b;  // outline, for the exact contour form factor
  std::vector<Vec3> interior;        // curved only: corners on no outline edge (clusters.h)
  SampleLanes sample;                // n samples spread by area, one per stratum
  size_t sample_count = 0;           // samples in `sample` (its lanes less the padding)
  // Where the shadow rays to the samples end: each stratum's point nearest the centroid of its
  // unshot power moved off the surface (off_surface
  // with the state's shadow offset), once per shot rather than once per receiving vertex.
  std::vector<float> end_x, end_y, end_z;
  Vec3 mean_unshot{0.0f};  // area-weighted mean unshot radiosity over the samples
  bool major = false;      // carried >= major_shot_fraction of the emitted energy
  // With light groups, a cluster's share per group (the solution's group count of them); the
  // rays and every choice of the shot are made from the source's whole values.
  std::vector<GroupShare> groups;
  // Near field: receivers closer to the source than `near_distance` weight its unshot radiosity
  // over the (about 16x more) fine samples, the points each stratum was made of (no more rays:
  // each takes the visibility of its stratum's sample), so a big source's variation is not read
  // off the one or two coarse samples that dominate the kernel up close.
  float near_distance = 0.0f;
  // How a receiver gets its form factor, by its distance from the centroid: within
  // single_distance the outline's contour integral in single precision, then in double (see
  // form_factor.h); beyond far_distance the midpoint rule over the samples, whose error falls
  // as (sample spacing / distance)^2.
  float single_distance = 0.0f, far_distance = 0.0f;
  // Fine samples grouped by stratum, each group padded to whole lanes: lanes [kLanes g,
  // kLanes (g + 1)) all belong to sample fine_group_parent[g], whose visibility they take.
  SampleLanes fine_sample;
  std::vector<uint32_t> fine_group_parent;
  // Per lane of fine_sample: the fine point's cell, the sub-triangle of its triangle's regular
  // grid whose centroid it is, as the edges u, v from the cell's first corner (0 for padding):
  // the cell is the point + (a - 1/3) u + (b - 1/3) v for a, b >= 0, a + b <= 1. Penumbra
  // rounds end their rays there (draw_ray_ends), on the source and nowhere else.
  std::vector<Vec3> fine_cell_u, fine_cell_v;
  // Russian roulette (Arvo and Kirk, "Particle transport and image synthesis", SIGGRAPH 1990)
  // over the receivers: where a point's gain is bounded by `level` times q(x) < 1 (roulette_q),
  // it gathers only when q(x) > its draw and divides its gain by q(x). The shot draws once
  // (roulette_draw, uniform in (0, 1)). A point of q(x) >= kLotsFromQ is in one of kRouletteLots
  // lots by its position, and lot k draws roulette_draw + k / kRouletteLots (mod 1); a fainter
  // point draws the shot's draw itself (point_draw). Each point's draw is uniform, so each stays
  // unbiased; but where one draw would have a faint shot's far wall gather all its points with
  // probability q or none, the lots have it gather a quarter of them (one lot, weighted 1 / q)
  // with probability 4q (for q <= 1/4): the wall's share of the shot keeps its mean with about a
  // quarter of the variance, and so does a room's total (its shell, the light it sends back).
  // Fainter points keep the shot's draw, so the far field (a building's other rooms) is skipped
  // box by box as often as with one draw (roulette_reaches_box). draw = 0: every point gathers,
  // as is.
  float roulette_draw = 0.0f, roulette_peak = 1.0f, roulette_reach2 = 0.0f;
  static constexpr uint32_t kRouletteLots = 4;
  static constexpr float kLotsFromQ = 0.01f;

  /// The draw a point at x of bound q (q < 1) gathers against (see roulette_draw).
  float point_draw(const Vec3& x, float q) const {
    if (q < kLotsFromQ) return roulette_draw;
    return lot_draw(uint32_t(position_seed(x) % kRouletteLots));
  }
  /// The draw of lot k: the shot's 23 bits (open_unit_draw) shifted by k whole lots, so exact.
  float lot_draw(uint32_t k) const {
    constexpr uint32_t kDraws = 1u << 23, kLotDraws = kDraws / kRouletteLots;
    const uint32_t m = uint32_t(roulette_draw * float(kDraws));  // roulette_draw = (m + 1/2) / 2^23
    return unit_draw((m + k * kLotDraws) % kDraws);
  }
  /// The least draw of any point of bound q: the shot's below kLotsFromQ, else the lowest lot's
  /// (the lot whose shift wraps the draw past 1).
  float least_draw(float q) const {
    if (q < kLotsFromQ) return roulette_draw;
    const uint32_t wrapped = uint32_t(roulette_draw * float(kRouletteLots));
    return lot_draw((kRouletteLots - wrapped) % kRouletteLots);
  }
  /// (m + 1/2) / 2^23 for the 23 bits m: a draw in (0, 1), exact in a float.
  static float unit_draw(uint32_t m) { return (float(m) + 0.5f) * 0x1p-23f; }

  /// q of a point at squared distance d2 from the source's box, at most h above a planar
  /// source's plane, whose tangent plane has the box's farthest corner m above it (h, m: +inf
  /// where not known). The form factor is at most A cos_s cos_r / (pi d^2), with cos_s <= h / d
  /// (every point of a planar source lies h below x, at least d away) and cos_r <= m / d: beside
  /// a floor or a ceiling, or on one, a far point gets little. Near the source (its bound on
  /// distance alone at least kCertain times the level) a point gathers for certain, cosines or
  /// not: the roulette's noise stays off the receivers that gain most from a shot.
  float roulette_q(float d2, float h, float m) const {
    if (!(d2 > 0.0f)) return roulette_peak;
    if (roulette_peak >= 1.0f && roulette_reach2 >= kCertain * d2) return 1.0f;
    const float d = std::sqrt(d2);
    const float cosines =
        std::min(1.0f, std::max(h, 0.0f) / d) * std::min(1.0f, std::max(m, 0.0f) / d);
    return std::min(roulette_peak, roulette_reach2 / d2 * cosines);
  }
  static constexpr float kCertain = 16.0f;
  /// The factor the gain at point x with normal n is multiplied by: 0 where it does not gather,
  /// 1 / q(x) where the roulette applies, else 1. `slack` bounds how far the point the gain is
  /// evaluated at lies from x (the gather's inset; at most kRouletteSlack times its triangle's
  /// extent).
  float roulette_weight(const Vec3& x, const Vec3& n, float slack) const {
    if (!(roulette_draw > 0.0f)) return 1.0f;
    const float q = roulette_q(distance2(box, x), height(x) + slack, facing(x, n) + slack);
    return q >= 1.0f ? 1.0f : (q > point_draw(x, q) ? 1.0f / q : 0.0f);
  }
  /// False when no point of `b` gathers (roulette_weight is 0 throughout, whatever its normal).
  bool roulette_reaches_box(const Aabb& b) const;
  /// False when no point of a triangle (its box `b`, a corner, its normal `n`) gathers.
  bool roulette_reaches_triangle(const Aabb& b, const Vec3& corner, const Vec3& n) const;
  /// False when every point of `b` is farther from the source than its reach at any height and
  /// facing (the roulette's bound on distance alone).
  bool roulette_distance_reaches(const Aabb& b) const;
  /// How far x lies above a planar source's plane (+inf for a curved one).
  float height(const Vec3& x) const {
    return planar ? glm::dot(x - centroid, axis) : std::numeric_limits<float>::infinity();
  }
  /// How far the source box's farthest corner lies above the plane through x with normal n.
  float facing(const Vec3& x, const Vec3& n) const { return highest_above(box, x, n); }
};

/// How far the point a gain is evaluated at may lie from its vertex, in extents of the vertex's
/// triangle: box tests (roulette_reaches_box, roulette_reaches_triangle) grow their bound by as
/// much.
inline constexpr float kRouletteSlack = 1e-3f;

/// The number of samples per side m (n = m * m) a source of box diagonal `extent` gets: the
/// least m in the options' range whose spacing (extent / m) is within the initial mesh's size.
int sample_grid_for(const SolverState& s, float extent);

/// Freezes cluster c as the source of the next shot. Its triangles are cut into fine points of
/// about equal area (regular barycentric grids, about 16 n in all), each with the unshot
/// radiosity interpolated on its own triangle's subdivision (design §5); the points are grouped
/// into n compact strata of equal area by median splits, and each stratum's sample sits at its
/// centroid with its area, mean normal and mean unshot radiosity (the shadow ray ends at the
/// stratum's point nearest the centroid of its unshot power, which lies on the surface).
ShotSource make_shot_source(const SolverState& s, int32_t c);

/// Whether a shot of `energy` (area x mean-channel radiosity, summed) is a major one: at least
/// SolverOptions::major_shot_fraction of the reference energy.
bool is_major_shot(const SolverState& s, double energy);

/// Cluster c frozen the same way as the source of its own emission E (its textures' included)
/// rather than its unshot radiosity: the direct light it gives (direct_light.h).
ShotSource make_emission_source(const SolverState& s, int32_t c);

/// Set `key`'s shadow-ray ends for `src`, x then y then z (3 x its ends) in `out`: each
/// stratum's ray ends at one of the stratum's fine points, drawn with probability proportional
/// to `weights` (one per lane of src.fine_sample: what the lane adds to a receiver's gain) or,
/// where null, to its power (area x |mean channel|), or to its area where the stratum has no
/// power (with `weights` all 0 in a stratum, it keeps the end src holds: the shot's, or at a
/// picture's pixel its set's, direct_light.h), by a fixed hash of (key, stratum), at a point of
/// the fine point's cell (fine_cell_u, fine_cell_v: on the source) drawn uniformly by another;
/// moved off the surface by `offset` as the shot's own ends are. A stratum without fine points
/// keeps the end src holds.
/// The same key gives the same ends on every run, thread and rank; different keys see a
/// stratum's visibility through different points. No allocation once `out` holds 3 x the ends.
void draw_ray_ends(const ShotSource& src, uint64_t key, float offset, const float* weights,
                   std::vector<float>& out);

/// The draw of 64 random bits: their top 23 bits plus a half, over 2^23, in (0, 1) and exact in
/// a float (at most 1 - 2^-24; 24 bits plus a half would round the largest up to 1).
float open_unit_draw(uint64_t bits);

/// Sets src's roulette for the shot numbered `shot` (its draw, fixed by the number: the same
/// for any thread or rank count, and again after a checkpoint): a point gathers for certain where
/// its gain may reach `level` (radiosity units). level <= 0: off.
void aim_roulette(ShotSource& src, float level, int64_t shot);

}  // namespace rad
