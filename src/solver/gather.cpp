#include "solver/gather.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <numbers>
#include <optional>
#include <span>

#include "core/denormals.h"
#include "core/position_bits.h"
#include "solver/form_factor.h"
#include "solver/light_source.h"

namespace rad {

namespace {

constexpr size_t W = SampleLanes::kLanes;

// W floats as one vector register (GCC vector extension): the kernel loops below keep their
// running sums in registers, which the auto-vectoriser did not (it stored them back to memory
// every group).
using Lanes = float __attribute__((vector_size(W * sizeof(float))));

Lanes load(const float* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

Lanes splat(float f) { return Lanes{} + f; }

float lane_sum(const Lanes& v) {  // fixed order: deterministic
  float t = 0.0f;
  for (size_t j = 0; j < W; ++j) t += v[j];
  return t;
}

// Per-lane partial sums of the kernel weights k, of k times the visible unshot radiosity, and
// (coarse samples) of the plain integrand A cos cos / (pi r^2) without EQ 7's regularising A.
struct KernelSums {
  Lanes w{}, r{}, g{}, b{}, p{};
  float weight() const { return lane_sum(w); }
  Vec3 weighted() const { return {lane_sum(r), lane_sum(g), lane_sum(b)}; }
  float plain() const { return lane_sum(p); }
};

// Per lane of a SampleLanes, the radiosity it shoots: its own (r, g, b) or a light group's
// share (ShotSource::groups).
struct LaneValues {
  const float *r, *g, *b;
};
LaneValues values_of(const SampleLanes& s) { return {s.r.data(), s.g.data(), s.b.data()}; }

// The EQ 7 weight A_i cos cos / (r^2 (pi r^2 + A_i)) of every lane of `s` (each sample with its
// own normal and area, 0 for padding) added to `sums`, the weights times `values`. The unshot
// radiosity of group g (lanes
// [W g, W (g + 1))) counts with factor visible[parent[g]] (1 or 0), or 1 when visible is null.
// Coarse samples also write each weight to k[i] and sum the plain integrand. Branch-free: each
// group of W lanes is a few vector instructions.
template <bool Coarse>
KernelSums add_kernels(const SampleLanes& s, LaneValues values, const Vec3& x, const Vec3& n,
                       const float* visible, const uint32_t* parent, float* k) {
  constexpr float pi = std::numbers::pi_v<float>;
  const Lanes xx = splat(x.x), xy = splat(x.y), xz = splat(x.z);
  const Lanes nx = splat(n.x), ny = splat(n.y), nz = splat(n.z);
  const Lanes zero{}, one = splat(1.0f), pis = splat(pi);
  KernelSums sums;
  for (size_t c = 0, group = 0; c < s.size(); c += W, ++group) {
    const Lanes dx = load(&s.x[c]) - xx, dy = load(&s.y[c]) - xy, dz = load(&s.z[c]) - xz;
    const Lanes r2 = dx * dx + dy * dy + dz * dz;
    const Lanes cr = nx * dx + ny * dy + nz * dz;
    const Lanes cs = -(load(&s.nx[c]) * dx + load(&s.ny[c]) * dy + load(&s.nz[c]) * dz);
    const Lanes a = load(&s.area[c]);
    // Selects, not branches: lanes that do not face get weight 0 and a harmless divisor.
    const auto faces = (cr > zero) & (cs > zero) & (r2 > zero) & (a > zero);
    const Lanes d2 = faces ? r2 : one, num = faces ? a * cr * cs : zero;
    const Lanes kv = num / (d2 * (pis * d2 + a));
    if constexpr (Coarse) {
      sums.p += num / (pis * d2 * d2);
      std::memcpy(&k[c], &kv, sizeof kv);
    }
    const Lanes kvis = visible ? kv * visible[parent[group]] : kv;
    if constexpr (!Coarse) {
      if (k) std::memcpy(&k[c], &kvis, sizeof kvis);
    }
    sums.w += kv;
    sums.r += kvis * load(&values.r[c]);
    sums.g += kvis * load(&values.g[c]);
    sums.b += kvis * load(&values.b[c]);
  }
  return sums;
}

// The sum of weights w times values v over n lanes (a multiple of W): a light group's share
// weighed as add_kernels weighed the whole, without evaluating the kernels again.
Vec3 weighted_sum(const float* w, LaneValues v, size_t n) {
  Lanes r{}, g{}, b{};
  for (size_t c = 0; c < n; c += W) {
    const Lanes k = load(&w[c]);
    r += k * load(&v.r[c]);
    g += k * load(&v.g[c]);
    b += k * load(&v.b[c]);
  }
  return {lane_sum(r), lane_sum(g), lane_sum(b)};
}

}  // namespace

int receiver_side(const ShotSource& src, const Vec3& x) {
  const Vec3 d = x - src.centroid;
  const float h = glm::dot(d, src.axis);
  // A point within a millionth of the extent of a planar source's plane lies in it (a coplanar
  // neighbour, in a rotated scene where coplanarity holds only to rounding): its form factor
  // is 0, and the outline's clipping would turn the rounding into polar-angle terms of O(1).
  if (src.planar) return h > 1e-6f * src.extent ? 1 : -1;
  const float len = glm::length(d);
  if (!(len > 0.0f)) return 0;
  const float cp = h / len, sp = std::sqrt(std::max(0.0f, 1.0f - cp * cp));
  if (len * (cp * src.cone_cos - sp * src.cone_sin) + src.offset_lo > 0.0f) return 1;
  const float upper = (cp >= src.cone_cos ? len : len * (cp * src.cone_cos + sp * src.cone_sin));
  return upper + src.offset_hi <= 0.0f ? -1 : 0;
}

namespace {

// The exact unoccluded form factor of the source at x with normal n (the analytic method of
// design §4), or nothing where it does not apply and the samples' EQ 7 sums stand: it needs x in
// front of every triangle of the source and, for a curved source cut by x's tangent plane, every
// corner off its outline in front of that plane too (else the plane may cut a loop that meets no
// outline edge, inside a dome, which the outline's clipping cannot see). Far away, with the source
// wholly and clearly in front of the tangent plane (every point of it lies within one extent of
// its centroid), the midpoint rule over the samples (sums.plain(): no grazing integrand for it
// to miss); nearer, the outline's contour integral, in single precision
// close up and double beyond.
std::optional<float> exact_form_factor(const Vec3& x, const Vec3& n, const ShotSource& src,
                                       int side, const KernelSums& sums) {
  if (side <= 0) return std::nullopt;
  if (!src.planar && lowest_above(src.box, x, n) <= 0.0f) {
    for (const Vec3& q : src.interior) {
      if (glm::dot(q - x, n) < 0.0f) return std::nullopt;
    }
  }
  const Vec3 to_source = src.centroid - x;
  const float d2 = glm::dot(to_source, to_source);
  if (d2 > src.far_distance * src.far_distance && glm::dot(n, to_source) > src.extent) {
    return std::clamp(sums.plain(), 0.0f, 1.0f);
  }
  const bool close = d2 < src.single_distance * src.single_distance;
  return point_to_outline_form_factor(x, n, src.edge_a.data(), src.edge_b.data(), src.edge_a.size(),
                                      src.axis, close ? Arithmetic::Single : Arithmetic::Double);
}

// One fan of shadow rays from x (moved off its surface) to the ends (ex, ey, ez, indexed by
// sample) of the samples active[which[0 .. count)], answers into blocked[0 .. count).
void trace_fan_to(const Vec3& x, const Vec3& n, const float* ex, const float* ey, const float* ez,
                  const uint32_t* which, size_t count, const VisibilityBackend& vis,
                  const GatherSettings& st, GatherScratch& scratch, uint8_t* blocked) {
  scratch.end_x.resize(count), scratch.end_y.resize(count), scratch.end_z.resize(count);
  for (size_t j = 0; j < count; ++j) {
    const uint32_t i = scratch.active[which ? which[j] : j];
    scratch.end_x[j] = ex[i];
    scratch.end_y[j] = ey[i];
    scratch.end_z[j] = ez[i];
  }
  const SegmentFan fan{off_surface(x, n, st.shadow_offset), scratch.end_x.data(),
                       scratch.end_y.data(), scratch.end_z.data(), count};
  vis.occluded_fan(fan, std::span<uint8_t>(blocked, count), scratch.stats.rays);
}

// The same to the shot's own ends.
void trace_fan(const Vec3& x, const Vec3& n, const ShotSource& src, const uint32_t* which,
               size_t count, const VisibilityBackend& vis, const GatherSettings& st,
               GatherScratch& scratch, uint8_t* blocked) {
  trace_fan_to(x, n, src.end_x.data(), src.end_y.data(), src.end_z.data(), which, count, vis, st,
               scratch, blocked);
}

// Whether `src` gets penumbra rounds: a major shot with fine points to draw from, whose mean
// sample carries at least st.penumbra_sample_energy. A sample's step in a penumbra is worth
// what it carries: the lamps' first shots step by a sixteenth of their light, and the rounds go
// there; a wall shot again and again carries a few percent over 64 samples, its steps are small
// and its shadow rays many, and answers kept for its own ends are what keep it cheap. In a
// picture (st.penumbra_every_source) every source with fine points gets them.
bool penumbra_source(const ShotSource& src, const GatherSettings& st) {
  if (src.fine_sample.empty() || src.sample_count == 0) return false;
  if (st.penumbra_every_source) return true;
  if (!src.major) return false;
  const double energy = double(src.area) * std::abs(double(mean_component(src.mean_unshot)));
  return energy >= st.penumbra_sample_energy * double(src.sample_count);
}

// Whether a ray to a corner of a planar source's outline finds it `hidden` otherwise than the
// vertex's rays to the samples all did. Those rays end inside the strata, so a vertex near a
// penumbra's edge may find them all blocked though a sliver of the source shows, or all clear
// though a sliver is hidden. A straight occluding edge cuts a convex source into two parts each
// holding one of its corners, so rays to the corners see both. At most kCornerProbes corners,
// evenly spaced along the outline, each a thousandth of the way to the centroid.
constexpr size_t kCornerProbes = 8;
bool corners_disagree(const Vec3& x, const Vec3& n, const ShotSource& src, bool hidden,
                      const VisibilityBackend& vis, const GatherSettings& st,
                      GatherScratch& scratch) {
  const size_t corners = src.edge_a.size();
  if (!src.planar || corners == 0) return false;
  const size_t step = (corners + kCornerProbes - 1) / kCornerProbes;
  scratch.end_x.resize(kCornerProbes), scratch.end_y.resize(kCornerProbes);
  scratch.end_z.resize(kCornerProbes);
  size_t count = 0;
  for (size_t i = 0; i < corners && count < kCornerProbes; i += step) {
    const Vec3 c = src.edge_a[i] + (src.centroid - src.edge_a[i]) * 1e-3f;
    if (!(glm::dot(c - x, n) > 0.0f)) continue;  // behind the vertex: no light from there
    const Vec3 end = off_surface(c, src.axis, st.shadow_offset);
    scratch.end_x[count] = end.x, scratch.end_y[count] = end.y, scratch.end_z[count] = end.z;
    ++count;
  }
  if (count == 0) return false;
  scratch.blocked.resize(std::max(scratch.blocked.size(), count));
  const SegmentFan fan{off_surface(x, n, st.shadow_offset), scratch.end_x.data(),
                       scratch.end_y.data(), scratch.end_z.data(), count};
  vis.occluded_fan(fan, std::span<uint8_t>(scratch.blocked.data(), count), scratch.stats.rays);
  for (size_t j = 0; j < count; ++j)
    if (bool(scratch.blocked[j]) != hidden) return true;
  return false;
}

// Rounds that probe a point whose rays to the samples and to the corners all find the source
// hidden: it may still see the source through a gap narrower than a stratum (between a table's
// top and the wall behind it, between two boards), which no fixed end finds. The rest of the
// rounds follow only where a probe finds some of the source.
constexpr uint32_t kProbeRounds = 2;

// scratch.clear[j] for the active samples j < na, from their answers in scratch.blocked: 1 where
// they all find the source clear and so do the rays to its corners; 0 where they all find it
// hidden and so do the corners and kProbeRounds rounds; otherwise (a penumbra, or a gap the
// probes see through), for a source that gets them (penumbra_source), the part of
// st.penumbra_rays rounds' rays that reach it, round r to the ends draw_ray_ends gives the key of
// (x, r), each stratum's end drawn by what its fine points add to x's gain (their kernel at x
// times their unshot radiosity). Drawn so, the part of a stratum's rays that reach x estimates
// its visible part weighed as its gain is: up close the kernel varies across a stratum many
// times over (a face 15 cm from a window sees a 5 cm band along its near edge through a gap
// under a board; the band weighs three times its share of the area), and ends drawn by area
// would read the band at its area. The first pass's answers, one per stratum at the ends src
// holds (the shot's; at a picture's pixel, its set's), count too when `fixed_count`: far from the
// source (beyond its near field), where the kernel varies little across a stratum, they are samples
// as good as the drawn ones and spread evenly; near it they would weigh each stratum's light at its
// power centroid. Where the probes found the source they never count: all hidden is why the point
// probed. The rounds' answers are not kept: their ends move with the point. `fine_kernel`: the fine
// samples' kernels at x where the caller has them already, else null.
void penumbra_rounds(const Vec3& x, const Vec3& n, const ShotSource& src, size_t na,
                     bool fixed_count, const float* fine_kernel, const VisibilityBackend& vis,
                     const GatherSettings& st, GatherScratch& scratch) {
  scratch.clear.resize(na);
  size_t blocked = 0;
  for (size_t j = 0; j < na; ++j) {
    blocked += scratch.blocked[j];
    scratch.clear[j] = scratch.blocked[j] ? 0.0f : 1.0f;
  }
  if (st.penumbra_rays == 0 || !penumbra_source(src, st)) return;
  const bool hidden = blocked == na;
  const bool agree =
      (blocked == 0 || hidden) && !corners_disagree(x, n, src, hidden, vis, st, scratch);
  if (agree && !hidden) return;
  // The last probing round: where every ray so far agrees the source is hidden, the rounds end
  // there unless one of them finds some of it.
  const uint32_t probes = agree ? std::min(kProbeRounds, st.penumbra_rays) : 0;
  // Neighbouring points see a stratum through different points, a point always the same.
  const uint64_t seed = position_seed(x);
  const size_t m = src.end_x.size();
  const SampleLanes& fine = src.fine_sample;
  scratch.draw_weight.resize(fine.size());
  float* const w = scratch.draw_weight.data();
  if (fine_kernel) {
    std::copy(fine_kernel, fine_kernel + fine.size(), w);
  } else {
    add_kernels<false>(fine, values_of(fine), x, n, nullptr, nullptr, w);
  }
  for (size_t i = 0; i < fine.size(); ++i) w[i] *= std::abs(mean_component(fine.value(i)));
  fixed_count = fixed_count && probes == 0;
  if (!fixed_count) std::fill(scratch.clear.begin(), scratch.clear.end(), 0.0f);
  scratch.blocked.resize(na);
  for (uint32_t r = 1; r <= st.penumbra_rays; ++r) {
    draw_ray_ends(src, seed ^ (uint64_t(r) * 0x9e3779b97f4a7c15ull), st.shadow_offset,
                  scratch.draw_weight.data(), scratch.round_ends);
    const float* e = scratch.round_ends.data();
    trace_fan_to(x, n, e, e + m, e + 2 * m, nullptr, na, vis, st, scratch, scratch.blocked.data());
    for (size_t j = 0; j < na; ++j) scratch.clear[j] += scratch.blocked[j] ? 0.0f : 1.0f;
    if (r == probes && std::all_of(scratch.clear.begin(), scratch.clear.begin() + ptrdiff_t(na),
                                   [](float c) { return c == 0.0f; }))
      return;
  }
  const float mean = 1.0f / float(st.penumbra_rays + (fixed_count ? 1 : 0));
  for (size_t j = 0; j < na; ++j) scratch.clear[j] *= mean;
}

// scratch.blocked[j] for the active sample scratch.active[j], j < na: traced, or read from the
// kept answers where the vertex was traced since the sample's ray end last moved; the ones
// traced are kept.
void trace_active(const Vec3& x, const Vec3& n, const ShotSource& src, size_t na,
                  const VisibilityBackend& vis, const GatherSettings& st, GatherScratch& scratch,
                  const VertexRays* kept) {
  scratch.blocked.resize(na);
  if (!kept) {
    trace_fan(x, n, src, nullptr, na, vis, st, scratch, scratch.blocked.data());
    return;
  }
  uint64_t* bits = kept->record + 1;
  const uint64_t traced = kept->record[0];
  scratch.unknown.resize(na);
  size_t nu = 0;
  for (size_t j = 0; j < na; ++j) {
    const uint32_t i = scratch.active[j];
    if (traced != 0 && kept->moved[i] <= traced) {
      scratch.blocked[j] = uint8_t((bits[i / 64] >> (i % 64)) & 1u);
    } else {
      scratch.unknown[nu++] = uint32_t(j);
    }
  }
  scratch.stats.kept_answers += na - nu;
  if (nu > 0) {
    // Answers land at the end of `blocked` (sized for them), then go to their places.
    scratch.blocked.resize(na + nu);
    uint8_t* fresh = scratch.blocked.data() + na;
    trace_fan(x, n, src, scratch.unknown.data(), nu, vis, st, scratch, fresh);
    for (size_t u = 0; u < nu; ++u) {
      const uint32_t j = scratch.unknown[u], i = scratch.active[j];
      scratch.blocked[j] = fresh[u];
      const uint64_t bit = uint64_t(1) << (i % 64);
      bits[i / 64] = fresh[u] ? bits[i / 64] | bit : bits[i / 64] & ~bit;
    }
  }
  kept->record[0] = kept->epoch;
}

// gather_from_source without the roulette. `groups`, when not empty, must hold 0 on entry.
Vec3 gather_all(const Vec3& x_vertex, const Vec3& n, const Vec3& centroid, const ShotSource& src,
                const VisibilityBackend& vis, const GatherSettings& st, GatherScratch& scratch,
                const VertexRays* kept, std::span<Vec3> groups) {
  const Vec3 x = x_vertex + (centroid - x_vertex) * st.inset;
  // One-sided source: a receiver behind every one of its triangles gets nothing.
  const int side = receiver_side(src, x);
  if (side < 0) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  // EQ 7 weights of the coarse samples; the active ones face the receiver and get a ray. The
  // active list is built without branches: which samples face the receiver changes from vertex
  // to vertex.
  const SampleLanes& sm = src.sample;
  const size_t ns = sm.size();
  scratch.weight.resize(ns);
  scratch.active.resize(ns);
  float* k = scratch.weight.data();
  const KernelSums sums = add_kernels<true>(sm, values_of(sm), x, n, nullptr, nullptr, k);
  const float weight_sum = sums.weight();
  const Vec3 unoccluded = sums.weighted();
  size_t na = 0;
  for (size_t i = 0; i < ns; ++i) {
    scratch.active[na] = uint32_t(i);
    na += k[i] > 0.0f ? 1 : 0;
  }

  // The form factor: exact where it applies, else EQ 7 as it stands (the areas are in the
  // weights). Gain = scale * sum(k * dB * visibility).
  const std::optional<float> ff = st.method == FormFactorMethod::Analytic
                                      ? exact_form_factor(x, n, src, side, sums)
                                      : std::nullopt;
  // No exact form factor: a curved source seen from close to its surface (a cushion from the
  // seat beside it). A coarse sample sits at its stratum's centroid, inside the curve, with the
  // stratum's mean normal, and weighs what lies close far worse than EQ 7 over the fine points,
  // each with its stratum's visibility (test Gather.BesideACurvedSource...: 56% off against
  // 23%). Every stratum then gets a ray: one whose mean normal faces away may still hold points
  // that face the receiver.
  const bool fine_eq7 = st.method == FormFactorMethod::Analytic && !ff && !src.fine_sample.empty();
  if (fine_eq7) {
    na = 0;
    for (size_t i = 0; i < ns; ++i) {
      scratch.active[na] = uint32_t(i);
      na += sm.area[i] > 0.0f ? 1 : 0;
    }
  }
  // Near field (exact form factor only): the source's unshot radiosity weighed over the fine
  // samples, each taking its stratum's visibility. Where the receiver's tangent plane cuts the
  // source, a stratum whose sample lies behind that plane may hold fine points in front, which
  // weigh most when the receiver is close. Its ray to the stratum's own end would run behind
  // the receiver and say nothing of them; taking them as seen would let light through (a
  // board's side in a slot a fraction of a millimetre from the panel beside it, at right angles
  // to the wall behind, took the wall's light through the panel). Such a stratum (an *edge
  // stratum*) gets a ray of its own, to its fine point in front that weighs most.
  // Only a source reaching behind the tangent plane (not merely touching it, as a wall does the
  // floor) can have edge strata: elsewhere the fine weights wait until the visibility is known,
  // and take it in the same pass.
  const size_t nf = src.fine_sample.size();
  float* const fine_k = (scratch.fine_weight.resize(nf), scratch.fine_weight.data());
  float fine_sum = 0.0f;
  Vec3 fine_unoccluded(0.0f);
  const bool near_field = glm::dot(x - src.centroid, src.axis) < src.near_distance;
  const bool near = ff && !src.fine_sample.empty() && near_field;
  bool cut_by_plane = near && lowest_above(src.box, x, n) < 0.0f;
  if (cut_by_plane) {
    const KernelSums fs = add_kernels<false>(src.fine_sample, values_of(src.fine_sample), x, n,
                                             nullptr, nullptr, fine_k);
    fine_sum = fs.weight();
    fine_unoccluded = fs.weighted();
    cut_by_plane = fine_sum > 0.0f;
  }
  // The active samples [0, na) get the shot's rays; the edge strata [na, na + ne) their own.
  size_t ne = 0;
  if (cut_by_plane) {
    scratch.stratum_weight.assign(ns, 0.0f);
    scratch.edge_lane.assign(ns, 0u);
    for (size_t c = 0, group = 0; c < nf; c += W, ++group) {
      const uint32_t g = src.fine_group_parent[group];
      float& w = scratch.stratum_weight[g];
      uint32_t& best = scratch.edge_lane[g];
      for (size_t j = 0; j < W; ++j) {
        if (fine_k[c + j] > fine_k[best] || w == 0.0f) best = uint32_t(c + j);
        w += fine_k[c + j];
      }
    }
    for (size_t i = 0; i < ns; ++i) {
      if (k[i] <= 0.0f && scratch.stratum_weight[i] > 0.0f) scratch.active[na + ne++] = uint32_t(i);
    }
  }
  if (ff ? *ff <= 0.0f : na + ne == 0) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  ++scratch.stats.vertex_evaluations;
  const float scale = ff ? (weight_sum > 0.0f ? *ff / weight_sum : 0.0f) : 1.0f;
  // An edge stratum's ray: to its heaviest fine point, moved off the surface.
  auto trace_edges = [&](size_t from, size_t count, uint8_t* blocked) {
    scratch.end_x.resize(count), scratch.end_y.resize(count), scratch.end_z.resize(count);
    for (size_t j = 0; j < count; ++j) {
      const uint32_t lane = scratch.edge_lane[scratch.active[from + j]];
      const Vec3 e =
          off_surface(src.fine_sample.point(lane), src.fine_sample.normal(lane), st.shadow_offset);
      scratch.end_x[j] = e.x, scratch.end_y[j] = e.y, scratch.end_z[j] = e.z;
    }
    const SegmentFan fan{off_surface(x, n, st.shadow_offset), scratch.end_x.data(),
                         scratch.end_y.data(), scratch.end_z.data(), count};
    vis.occluded_fan(fan, std::span<uint8_t>(blocked, count), scratch.stats.rays);
  };

  // Visibility of the active samples: traced, or all visible without shadows or below the cut.
  // The cut weighs the coarse samples, which say nothing of the fine points' EQ 7 (every coarse
  // weight may be 0 where fine points face the receiver): there every stratum is traced.
  // Near the source the fine samples' weights say what the gain is and which stratum weighs most.
  const Vec3 unoccluded_gain =
      cut_by_plane ? fine_unoccluded * (*ff / fine_sum) : unoccluded * scale;
  const float* const weighs = cut_by_plane ? scratch.stratum_weight.data() : k;
  const bool cut =
      !fine_eq7 && max_component(glm::abs(unoccluded_gain)) < st.cut;  // |.|: negative edits
  if (st.shadows && cut && na + ne > 0) {
    // Below the cut one ray, to the sample that weighs most, stands for all: a gain taken
    // unoccluded would go through walls, and in a building many small shots add such gains up
    // everywhere, too bright and with more energy left to shoot.
    scratch.stats.intensity_cuts += na + ne - 1;
    size_t best = 0;
    for (size_t j = 1; j < na + ne; ++j)
      if (weighs[scratch.active[j]] > weighs[scratch.active[best]]) best = j;
    uint8_t blocked = 0;
    if (best < na) {
      const uint32_t one = uint32_t(best);
      trace_fan(x, n, src, &one, 1, vis, st, scratch, &blocked);
    } else {
      trace_edges(best, 1, &blocked);
    }
    if (blocked) return Vec3(0.0f);
  }
  const bool traced = st.shadows && !cut && na + ne > 0;
  if (traced) {
    trace_active(x, n, src, na, vis, st, scratch, kept);
    // The fixed ends count beyond the near field, whichever way the form factor is taken.
    penumbra_rounds(x, n, src, na, !(near_field || fine_eq7), cut_by_plane ? fine_k : nullptr, vis,
                    st, scratch);
    if (ne > 0) {
      scratch.blocked.resize(ne);
      trace_edges(na, ne, scratch.blocked.data());
      scratch.clear.resize(na + ne);
      for (size_t j = 0; j < ne; ++j) scratch.clear[na + j] = scratch.blocked[j] ? 0.0f : 1.0f;
    }
  }
  na += ne;

  // From here on the gain is linear in the values the source shoots: the light groups' shares
  // (ShotSource::groups) go through the same weights and visibility as the whole, so they add
  // up to it.
  auto each_group = [&](auto&& gain) {
    for (size_t g = 0; g < groups.size(); ++g) groups[g] = gain(src.groups[g]);
  };
  auto lanes = [](const std::vector<float>& r, const std::vector<float>& g,
                  const std::vector<float>& b) {
    return LaneValues{r.data(), g.data(), b.data()};
  };
  if (fine_eq7) {
    scratch.coarse_visible.assign(ns, traced ? 0.0f : 1.0f);
    if (traced) {
      for (size_t j = 0; j < na; ++j) scratch.coarse_visible[scratch.active[j]] = scratch.clear[j];
    }
    const Vec3 whole =
        add_kernels<false>(src.fine_sample, values_of(src.fine_sample), x, n,
                           scratch.coarse_visible.data(), src.fine_group_parent.data(),
                           groups.empty() ? nullptr : fine_k)
            .weighted();
    each_group([&](const GroupShare& gs) {
      return weighted_sum(fine_k, lanes(gs.fine_r, gs.fine_g, gs.fine_b), nf);
    });
    return whole;
  }
  if (near) {
    // Each fine sample's weight times its stratum's visibility, over the unoccluded weights.
    scratch.coarse_visible.assign(ns, traced ? 0.0f : 1.0f);
    if (traced) {
      for (size_t j = 0; j < na; ++j) scratch.coarse_visible[scratch.active[j]] = scratch.clear[j];
    }
    Vec3 whole(0.0f);
    if (cut_by_plane) {
      for (size_t c = 0, group = 0; c < nf; c += W, ++group) {
        const float v = scratch.coarse_visible[src.fine_group_parent[group]];
        for (size_t j = 0; j < W; ++j) fine_k[c + j] *= v;
      }
      whole = weighted_sum(fine_k, values_of(src.fine_sample), nf);
    } else {
      const KernelSums fs =
          add_kernels<false>(src.fine_sample, values_of(src.fine_sample), x, n,
                             scratch.coarse_visible.data(), src.fine_group_parent.data(), fine_k);
      fine_sum = fs.weight();
      whole = fs.weighted();
    }
    if (fine_sum > 0.0f) {
      const float to_gain = *ff / fine_sum;
      each_group([&](const GroupShare& gs) {
        return weighted_sum(fine_k, lanes(gs.fine_r, gs.fine_g, gs.fine_b), nf) * to_gain;
      });
      return whole * to_gain;
    }
  }
  // The visible part of the source holds no sample (a sliver above the tangent plane): it is
  // taken unoccluded with the source's mean unshot radiosity.
  if (ff && weight_sum <= 0.0f) {
    each_group([&](const GroupShare& gs) { return gs.mean_unshot * *ff; });
    return src.mean_unshot * *ff;
  }
  if (!traced) {
    each_group(
        [&](const GroupShare& gs) { return weighted_sum(k, lanes(gs.r, gs.g, gs.b), ns) * scale; });
    return unoccluded * scale;
  }
  // The visible samples summed afresh (not the blocked ones subtracted): a vertex in full
  // umbra gets exactly zero.
  auto visible_gain = [&](LaneValues v) {
    Vec3 visible(0.0f);
    for (size_t j = 0; j < na; ++j) {
      const float c = scratch.clear[j];  // k x 1 is k: all-or-nothing points as they were
      const uint32_t i = scratch.active[j];
      if (c > 0.0f) visible += Vec3(v.r[i], v.g[i], v.b[i]) * (k[i] * c);
    }
    return visible * scale;
  };
  each_group([&](const GroupShare& gs) { return visible_gain(lanes(gs.r, gs.g, gs.b)); });
  return visible_gain(values_of(sm));
}

// gather_from_source for a light: its illuminance at x times what it shoots, times the part of
// its shadow rays that reach it (one for a point or spot light, kSunRays for the sun; below the
// intensity cut one stands for all, as for a surface). All of it is its own light group's.
Vec3 gather_light(const Vec3& x_vertex, const Vec3& n, const Vec3& centroid, const ShotSource& src,
                  const VisibilityBackend& vis, const GatherSettings& st, GatherScratch& scratch) {
  const Vec3 x = x_vertex + (centroid - x_vertex) * st.inset;
  const float e = light_illuminance(src, x, n);
  if (!(e > 0.0f)) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  ++scratch.stats.vertex_evaluations;
  const Vec3 gain = src.light_colour * e;
  if (!st.shadows) return gain;
  const size_t all = light_ray_count(src);
  const bool cut = max_component(glm::abs(gain)) < st.cut;
  const size_t rays = cut ? 1 : all;
  if (cut) scratch.stats.intensity_cuts += all - 1;
  const Vec3 from = off_surface(x, n, st.shadow_offset);
  scratch.end_x.resize(rays), scratch.end_y.resize(rays), scratch.end_z.resize(rays);
  for (size_t k = 0; k < rays; ++k) {
    const Vec3 end = light_ray_end(src, from, k);
    scratch.end_x[k] = end.x, scratch.end_y[k] = end.y, scratch.end_z[k] = end.z;
  }
  scratch.blocked.resize(rays);
  const SegmentFan fan{from, scratch.end_x.data(), scratch.end_y.data(), scratch.end_z.data(),
                       rays};
  vis.occluded_fan(fan, std::span<uint8_t>(scratch.blocked.data(), rays), scratch.stats.rays);
  size_t clear = 0;
  for (size_t k = 0; k < rays; ++k) clear += scratch.blocked[k] ? 0 : 1;
  return clear == rays ? gain : gain * (float(clear) / float(rays));
}

}  // namespace

Vec3 gather_from_source(const Vec3& x_vertex, const Vec3& n, const Vec3& centroid,
                        const ShotSource& src, const VisibilityBackend& vis,
                        const GatherSettings& st, GatherScratch& scratch, const VertexRays* kept,
                        std::span<Vec3> groups) {
  // The roulette looks at the vertex itself, not the point moved inside its polygon: coplanar
  // polygons sharing a vertex make the same choice for it. Its cosine bounds allow for the move.
  assert(st.inset <= kRouletteSlack);
  std::fill(groups.begin(), groups.end(), Vec3(0.0f));
  if (src.light >= 0) {
    const Vec3 h = gather_light(x_vertex, n, centroid, src, vis, st, scratch);
    if (!groups.empty()) groups[size_t(src.light_group)] = h;
    return h;
  }
  assert(groups.empty() || groups.size() == src.groups.size());
  const float w = src.roulette_weight(x_vertex, n, st.inset * glm::length(centroid - x_vertex));
  if (w == 0.0f) {
    ++scratch.stats.roulette;
    return Vec3(0.0f);
  }
  const Vec3 h = gather_all(x_vertex, n, centroid, src, vis, st, scratch, kept, groups);
  if (w == 1.0f) return h;
  for (Vec3& g : groups) g *= w;
  return h * w;
}

void parallel_gather(size_t n, size_t grain, SolverStats& stats,
                     const std::function<void(size_t, size_t, GatherScratch&)>& body) {
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain), [&](const auto& range) {
    const ScopedFlushDenormals ftz;  // once per chunk, not per ray batch (see denormals.h)
    body(range.begin(), range.end(), scratch.local());
  });
  for (const GatherScratch& sc : scratch) stats += sc.stats;
}

}  // namespace rad
