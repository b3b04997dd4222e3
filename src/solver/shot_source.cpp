#include "solver/shot_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "core/planar_geometry.h"
#include "mesh/sample_points.h"
#include "solver/solver_state.h"
#include "visibility/segment.h"

namespace rad {

namespace {
// Where, in source extents, single-precision contours stop and where the midpoint rule takes
// over; errors measured by tests/solver/gather_test.cpp.
constexpr float kSingleExtents = 6.0f;
constexpr float kFarFieldExtents = 24.0f;
// Fine points per sample, about.
constexpr int kFinePerSample = 16;

struct FinePoint {
  Vec3 position, normal, unshot;
  float area;
  Vec3 cell_u, cell_v;  // ShotSource::fine_cell_u, fine_cell_v
};

// Splits points[lo, hi) into `groups` strata of about equal area by median cuts along the
// longest axis of their box, writing each point's stratum to stratum_of.
void stratify(std::vector<FinePoint>& points, size_t lo, size_t hi, uint32_t groups,
              uint32_t first_group, std::vector<uint32_t>& order,
              std::vector<uint32_t>& stratum_of) {
  if (groups <= 1) {
    for (size_t i = lo; i < hi; ++i) stratum_of[order[i]] = first_group;
    return;
  }
  Aabb box;
  double total = 0.0;
  for (size_t i = lo; i < hi; ++i)
    box.extend(points[order[i]].position), total += points[order[i]].area;
  const int axis = box.widest_axis();
  std::sort(order.begin() + long(lo), order.begin() + long(hi), [&](uint32_t a, uint32_t b) {
    const float pa = points[a].position[axis], pb = points[b].position[axis];
    return pa < pb || (pa == pb && a < b);
  });
  const uint32_t left = groups / 2;
  const double target = total * double(left) / double(groups);
  size_t mid = lo;
  double acc = 0.0;
  while (mid < hi && acc + 0.5 * points[order[mid]].area < target) acc += points[order[mid++]].area;
  mid = std::clamp(mid, lo + left, hi - (groups - left));  // each stratum keeps a point
  stratify(points, lo, mid, left, first_group, order, stratum_of);
  stratify(points, mid, hi, groups - left, first_group + left, order, stratum_of);
}

}  // namespace

void SampleLanes::push_back(const Vec3& p, const Vec3& n, float a, const Vec3& u) {
  x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  nx.push_back(n.x), ny.push_back(n.y), nz.push_back(n.z);
  area.push_back(a);
  r.push_back(u.x), g.push_back(u.y), b.push_back(u.z);
}

void SampleLanes::pad() {
  while (size() % kLanes != 0) push_back(Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, Vec3(0.0f));
}

int sample_grid_for(const SolverState& s, float extent) {
  const float first = float(s.options.sample_grid);
  const float last = float(std::max(s.options.sample_grid, s.options.max_sample_grid));
  const float wanted = s.scene.max_size > 0.0f ? std::ceil(extent / s.scene.max_size) : first;
  return int(std::clamp(wanted, first, last));
}

namespace {

// make_shot_source with the radiosity the source shoots read by value(polygon, vertex).
template <typename Value>
ShotSource make_cluster_source(const SolverState& s, int32_t c, Value value) {
  const Triangles& tris = s.solution.hierarchy->triangles;
  const Clusters& clusters = s.scene.clusters;
  const size_t ci = size_t(c);
  ShotSource src;
  src.cluster = c;
  src.planar = clusters.planar[ci];
  src.centroid = clusters.centroid[ci], src.axis = clusters.axis[ci];
  src.cone_cos = clusters.cone_cos[ci], src.cone_sin = clusters.cone_sin[ci];
  src.offset_lo = clusters.offset_lo[ci], src.offset_hi = clusters.offset_hi[ci];
  src.box = clusters.box[ci];
  src.area = clusters.area[ci];
  src.extent = clusters.extent[ci];
  src.edge_a.assign(clusters.edge_a.begin() + clusters.edge_first[ci],
                    clusters.edge_a.begin() + clusters.edge_first[ci + 1]);
  src.edge_b.assign(clusters.edge_b.begin() + clusters.edge_first[ci],
                    clusters.edge_b.begin() + clusters.edge_first[ci + 1]);
  src.interior.assign(clusters.interior.begin() + clusters.interior_first[ci],
                      clusters.interior.begin() + clusters.interior_first[ci + 1]);

  const int m = sample_grid_for(s, src.extent);
  const uint32_t n = uint32_t(m * m);
  // Fine points: each triangle cut into q x q by a regular barycentric grid, q the least that
  // makes its pieces no bigger than A / (16 n) (a single triangle gets the (4m)^2 grid).
  std::vector<FinePoint> fine;
  const int max_q = int(s.scene.barycentric_grids.size()) - 1;
  for (uint32_t j = clusters.first[ci]; j < clusters.first[ci + 1]; ++j) {
    const uint32_t t = clusters.polygons[j];
    const float share = float(kFinePerSample) * float(n) * tris.area[t] / src.area;
    const int q = std::clamp(int(std::ceil(std::sqrt(share) - 1e-4f)), 1, max_q);
    const float piece = tris.area[t] / float(q * q);
    const auto& c3 = tris.corners[t];
    const Vec3 cell_u = (c3[1] - c3[0]) / float(q), cell_v = (c3[2] - c3[0]) / float(q);
    for (const Vec3& w : s.scene.barycentric_grids[size_t(q)]) {
      // An upward cell's centroid lies a third of a step into it along b, a downward one's two
      // thirds (regular_sample_barycentrics); a downward cell's edges run the other way.
      const float step = w.y * float(q);
      const float sign = step - std::floor(step) < 0.5f ? 1.0f : -1.0f;
      fine.push_back({c3[0] * w.x + c3[1] * w.y + c3[2] * w.z, tris.normal[t],
                      interpolate_at(
                          s.solution.mesh.polygons[t], [&](uint32_t v) { return value(t, v); }, w),
                      piece, cell_u * sign, cell_v * sign});
    }
  }
  const uint32_t strata = std::min<uint32_t>(n, uint32_t(fine.size()));
  std::vector<uint32_t> order(fine.size()), stratum_of(fine.size());
  std::iota(order.begin(), order.end(), 0u);
  stratify(fine, 0, fine.size(), strata, 0, order, stratum_of);

  // Per stratum: area, area centroid, mean normal, mean unshot radiosity, and the centroid of its
  // unshot power (weights |area x unshot|), near which its shadow ray ends.
  std::vector<double> area(strata, 0.0), power(strata, 0.0);
  std::vector<DVec3> centre(strata, DVec3(0.0)), unshot(strata, DVec3(0.0));
  std::vector<DVec3> normal(strata, DVec3(0.0)), power_centre(strata, DVec3(0.0));
  for (size_t i = 0; i < fine.size(); ++i) {
    const uint32_t g = stratum_of[i];
    const double a = fine[i].area, w = a * std::abs(double(mean_component(fine[i].unshot)));
    area[g] += a;
    power[g] += w;
    centre[g] += DVec3(fine[i].position) * a;
    power_centre[g] += DVec3(fine[i].position) * w;
    normal[g] += DVec3(fine[i].normal) * a;
    unshot[g] += DVec3(fine[i].unshot) * a;
  }
  std::vector<uint32_t> nearest(strata, 0);
  std::vector<float> best(strata, std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < fine.size(); ++i) {
    const uint32_t g = stratum_of[i];
    const DVec3 target = power[g] > 0.0 ? power_centre[g] / power[g] : centre[g] / area[g];
    const Vec3 d = fine[i].position - Vec3(target);
    if (glm::dot(d, d) < best[g]) best[g] = glm::dot(d, d), nearest[g] = uint32_t(i);
  }
  DVec3 mean(0.0);
  for (uint32_t g = 0; g < strata; ++g) {
    // The kernel is evaluated at the stratum's centroid with its mean normal (the midpoint rule,
    // second order in the spacing). The shadow ray ends on the surface where the stratum's power
    // is: at its area centroid, a stratum half under a block standing on it would have its lit
    // half's power blocked, and a floor's shot would lose what its lit part sends.
    const FinePoint& p = fine[nearest[g]];
    const Vec3 u(unshot[g] / area[g]);
    const DVec3 nm = normal[g] / std::max(glm::length(normal[g]), 1e-30);
    src.sample.push_back(Vec3(centre[g] / area[g]), Vec3(nm), float(area[g]), u);
    mean += unshot[g];
    const Vec3 end = off_surface(p.position, p.normal, s.scene.shadow_offset);
    src.end_x.push_back(end.x), src.end_y.push_back(end.y), src.end_z.push_back(end.z);
  }
  src.sample_count = strata;
  src.sample.pad();
  src.mean_unshot = Vec3(mean / double(src.area));

  // Fine points grouped by stratum (the order above sorted them within each stratum's range).
  std::vector<uint32_t> by_stratum(fine.size());
  std::iota(by_stratum.begin(), by_stratum.end(), 0u);
  std::stable_sort(by_stratum.begin(), by_stratum.end(),
                   [&](uint32_t a, uint32_t b) { return stratum_of[a] < stratum_of[b]; });
  for (size_t i = 0; i < by_stratum.size();) {
    const uint32_t g = stratum_of[by_stratum[i]];
    for (; i < by_stratum.size() && stratum_of[by_stratum[i]] == g; ++i) {
      const FinePoint& p = fine[by_stratum[i]];
      src.fine_sample.push_back(p.position, p.normal, p.area, p.unshot);
      src.fine_cell_u.push_back(p.cell_u), src.fine_cell_v.push_back(p.cell_v);
    }
    src.fine_sample.pad();
    src.fine_cell_u.resize(src.fine_sample.size(), Vec3(0.0f));
    src.fine_cell_v.resize(src.fine_sample.size(), Vec3(0.0f));
    src.fine_group_parent.resize(src.fine_sample.size() / SampleLanes::kLanes, g);
  }
  // Near field: closer than two sample spacings (extent / m).
  src.near_distance = 2.0f * src.extent / float(m);
  src.single_distance = kSingleExtents * src.extent;
  src.far_distance = kFarFieldExtents * src.extent;
  return src;
}

}  // namespace

ShotSource make_shot_source(const SolverState& s, int32_t c) {
  ShotSource src = make_cluster_source(
      s, c, [&](uint32_t t, uint32_t v) { return s.solution.vertex_states[t][v].unshot; });
  // Each light group's share, frozen the same way: the strata and lanes depend on the points
  // alone, so the shares' lanes line up with the source's.
  const size_t n = s.solution.group_count;
  for (size_t g = 0; g < n; ++g) {
    ShotSource part = make_cluster_source(
        s, c, [&](uint32_t t, uint32_t v) { return s.solution.group_states[t][v * n + g].unshot; });
    assert(part.sample.size() == src.sample.size());
    assert(part.fine_sample.size() == src.fine_sample.size());
    src.groups.push_back({std::move(part.sample.r), std::move(part.sample.g),
                          std::move(part.sample.b), std::move(part.fine_sample.r),
                          std::move(part.fine_sample.g), std::move(part.fine_sample.b),
                          part.mean_unshot});
  }
  return src;
}

ShotSource make_emission_source(const SolverState& s, int32_t c) {
  ShotSource src =
      make_cluster_source(s, c, [&](uint32_t t, uint32_t v) { return s.solution.emission(t, v); });
  // Major as its first shot was, so its direct light gets the same penumbra rounds.
  src.major =
      is_major_shot(s, double(src.area) * std::abs(double(mean_component(src.mean_unshot))));
  return src;
}

bool is_major_shot(const SolverState& s, double energy) {
  return s.options.major_shot_fraction > 0.0 &&
         energy >= s.options.major_shot_fraction * s.energy.reference_energy;
}

namespace {
// Whether a point of box b may gather from src (roulette_weight): b's nearest point to the
// source, at most `top` above a planar source's plane, its tangent plane `facing` below the
// source box's farthest corner at most (each grown by the slack of an evaluated point).
bool reaches(const ShotSource& src, const Aabb& b, float top, float facing) {
  if (!(src.roulette_draw > 0.0f)) return true;
  const float slack = kRouletteSlack * b.diagonal();
  const float q = src.roulette_q(distance2(src.box, b), top + slack, facing + slack);
  return q >= 1.0f || q > src.least_draw(q);
}

// The highest point of b above a planar source's plane (+inf for a curved source).
float top_of(const ShotSource& src, const Aabb& b) {
  return src.planar ? highest_above(b, src.centroid, src.axis)
                    : std::numeric_limits<float>::infinity();
}
}  // namespace

bool ShotSource::roulette_reaches_box(const Aabb& b) const {
  return reaches(*this, b, top_of(*this, b), std::numeric_limits<float>::infinity());
}

bool ShotSource::roulette_reaches_triangle(const Aabb& b, const Vec3& corner, const Vec3& n) const {
  // Every point of a flat triangle has the same tangent plane.
  return reaches(*this, b, top_of(*this, b), facing(corner, n));
}

bool ShotSource::roulette_distance_reaches(const Aabb& b) const {
  // reaches() with both cosines 1, without its square roots: the occluders chosen for a shot
  // are all looked at this way, every shot.
  if (!(roulette_draw > 0.0f)) return true;
  const float d2 = distance2(box, b);
  const float q = d2 * roulette_peak > roulette_reach2 ? roulette_reach2 / d2 : roulette_peak;
  return q >= 1.0f || q > least_draw(q);
}

void aim_roulette(ShotSource& src, float level, int64_t shot) {
  src.roulette_draw = 0.0f;
  if (!(level > 0.0f)) return;
  // The gain at x is at most the largest unshot radiosity on the source times its form factor,
  // itself at most min(1, A / (pi d^2)) times the cosines' bounds (roulette_q).
  float peak = 0.0f;
  for (const SampleLanes* l : {&src.sample, &src.fine_sample}) {
    for (const std::vector<float>* c : {&l->r, &l->g, &l->b}) {
      for (float v : *c) peak = std::max(peak, std::abs(v));
    }
  }
  if (!(peak > 0.0f && peak < std::numeric_limits<float>::max())) return;  // nothing, NaN, inf
  src.roulette_peak = std::min(1.0f, peak / level);
  src.roulette_reach2 = peak * src.area / (std::numbers::pi_v<float> * level);
  src.roulette_draw = open_unit_draw(splitmix64(uint64_t(shot)));
}

void draw_ray_ends(const ShotSource& src, uint64_t key, float offset, const float* weights,
                   std::vector<float>& out) {
  const size_t n = src.end_x.size();
  out.resize(3 * n);
  std::copy(src.end_x.begin(), src.end_x.end(), out.begin());
  std::copy(src.end_y.begin(), src.end_y.end(), out.begin() + long(n));
  std::copy(src.end_z.begin(), src.end_z.end(), out.begin() + long(2 * n));
  const SampleLanes& f = src.fine_sample;
  const size_t lanes = SampleLanes::kLanes;
  // Each stratum's lanes are one run of groups of lanes (make_shot_source).
  size_t group = 0;
  const size_t groups = src.fine_group_parent.size();
  while (group < groups) {
    const uint32_t g = src.fine_group_parent[group];
    size_t last = group;
    while (last < groups && src.fine_group_parent[last] == g) ++last;
    auto weight = [&](size_t i) {
      return weights ? double(weights[i])
                     : double(f.area[i]) * std::abs(double(mean_component(f.value(i))));
    };
    double power = 0.0, area = 0.0;
    for (size_t i = group * lanes; i < last * lanes; ++i) {
      power += weight(i);
      area += double(f.area[i]);
    }
    const bool by_power = power > 0.0;
    const double total = by_power ? power : area;
    // Weighed by a receiver, a stratum none of whose points gives it anything keeps its end: an
    // end drawn by area might lie behind the receiver's tangent plane.
    if (total > 0.0 && g < n && (by_power || !weights)) {
      const double draw =
          (double(splitmix64(key * 0x100000001b3ull + g) >> 11) + 0.5) * 0x1p-53 * total;
      double acc = 0.0;
      size_t pick = group * lanes;
      for (size_t i = group * lanes; i < last * lanes; ++i) {
        const double w = by_power ? weight(i) : double(f.area[i]);
        if (w <= 0.0) continue;
        pick = i;
        acc += w;
        if (acc >= draw) break;
      }
      // Anywhere in the fine point's cell (uniform over the sub-triangle): rays that end on the
      // fine points alone see a source's visibility in steps of a fine point however many of
      // them are drawn, the steps a penumbra would show. In the cell, not around the point: an
      // end beyond the source's edge may lie behind the wall it meets, and its blocked rays
      // would darken every vertex that sees the edge.
      const uint64_t bits = splitmix64(key * 0x9e3779b97f4a7c15ull + g);
      // The high 23 bits and the low 23 bits: two draws that never round to 1.
      const glm::vec2 w = fold_into_triangle(open_unit_draw(bits), open_unit_draw(bits << 41));
      const Vec3 at = f.point(pick) + src.fine_cell_u[pick] * (w.x - 1.0f / 3.0f) +
                      src.fine_cell_v[pick] * (w.y - 1.0f / 3.0f);
      const Vec3 end = off_surface(at, f.normal(pick), offset);
      out[g] = end.x, out[n + g] = end.y, out[2 * n + g] = end.z;
    }
    group = last;
  }
}

float open_unit_draw(uint64_t bits) { return ShotSource::unit_draw(uint32_t(bits >> 41)); }

}  // namespace rad
