#include "solver/occlusion_culling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

#include "core/planar_geometry.h"
#include "solver/shot_source.h"

namespace rad {

namespace {

constexpr uint32_t kLeafTriangles = 8;
// Occluders picked per shot, and how many of the best-placed regions are looked at for them.
constexpr size_t kOccluders = 32;  // one bit each in a mask
constexpr size_t kCandidates = 8 * kOccluders;

// Eight floats as one vector register (GCC vector extension): a box's corners, or the source's.
using Lanes = float __attribute__((vector_size(8 * sizeof(float))));

// The corners of a box: lane k takes hi on x when k & 1, on y when k & 2, on z when
// k & 4.
constexpr Lanes kSignX{-1, 1, -1, 1, -1, 1, -1, 1}, kSignY{-1, -1, 1, 1, -1, -1, 1, 1},
    kSignZ{-1, -1, -1, -1, 1, 1, 1, 1};

// The corners of `box` grown by `grow`, in the frame (u, w, n) at `origin`: per lane, its
// coordinate along `axis`.
Lanes corner_coordinates(const Aabb& box, double grow, const DVec3& origin, const DVec3& axis) {
  const DVec3 half = DVec3(box.extent()) * 0.5 + grow;
  const float c = float(glm::dot(DVec3(box.center()) - origin, axis));
  return c + kSignX * float(half.x * axis.x) + kSignY * float(half.y * axis.y) +
         kSignZ * float(half.z * axis.z);
}

// An occluder as one shot sees it: the source box's corners in its frame, and which side of its
// plane the source lies on.
struct ShotOccluder {
  const Occluder* occluder = nullptr;
  float side = 0.0f;  // +1 or -1
  Lanes su{}, sw{}, sd{};
};

enum class Cover { Hidden, Maybe, Never };

// Whether every segment from the source box to `box` (both grown by `margin`) crosses the
// occluder's triangles, `margin` clear of their union's edges (Hidden); if not, whether some box
// inside this one still may be hidden by it (Maybe) or none can (Never: no part of the box lies
// beyond the plane, or the crossings miss the occluder's 2D box). In single precision: the margin
// is far above the rounding of the crossings, except for corner pairs nearly parallel to the
// plane, whose rays then pass within rounding of the occluder's edge (the backends' ambiguity).
Cover covers(const ShotOccluder& so, const Aabb& box, float margin) {
  const Occluder& g = *so.occluder;
  const Lanes bd = corner_coordinates(box, margin, g.origin, g.normal) * so.side;
  const auto past = bd < -margin;  // per lane: -1 where beyond the plane
  int beyond = 0;
  for (size_t j = 0; j < 8; ++j) beyond += past[j] != 0 ? 1 : 0;
  if (beyond == 0) return Cover::Never;
  if (beyond < 8) return Cover::Maybe;
  // The segments between corners cross the plane at points whose hull holds every crossing of
  // a segment between the two boxes (central projections map hulls to hulls, from either end).
  const Lanes bu = corner_coordinates(box, margin, g.origin, g.u);
  const Lanes bw = corner_coordinates(box, margin, g.origin, g.w);
  Lanes lo_u = bu, hi_u = bu, lo_w = bw, hi_w = bw;  // overwritten by the first source corner
  for (size_t i = 0; i < 8; ++i) {
    const float ds = so.sd[i] * so.side, su = so.su[i], sw = so.sw[i];
    const Lanes t = ds / (ds - bd);
    const Lanes pu = su + (bu - su) * t, pw = sw + (bw - sw) * t;
    if (i == 0) {
      lo_u = hi_u = pu, lo_w = hi_w = pw;
    } else {
      lo_u = pu < lo_u ? pu : lo_u, hi_u = pu > hi_u ? pu : hi_u;
      lo_w = pw < lo_w ? pw : lo_w, hi_w = pw > hi_w ? pw : hi_w;
    }
  }
  DVec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (size_t j = 0; j < 8; ++j) {
    lo = glm::min(lo, DVec2(lo_u[j], lo_w[j])), hi = glm::max(hi, DVec2(hi_u[j], hi_w[j]));
  }
  lo -= double(margin), hi += double(margin);
  // A smaller box's crossings lie inside these.
  if (hi.x <= g.lo.x || hi.y <= g.lo.y || lo.x >= g.hi.x || lo.y >= g.hi.y) return Cover::Never;
  if (lo.x < g.lo.x || lo.y < g.lo.y || hi.x > g.hi.x || hi.y > g.hi.y) return Cover::Maybe;
  // The cells the rectangle meets: hidden if every one is full (fused pieces lie within the
  // ambiguity distance of one plane, so no ray the backends agree on passes where they abut),
  // never if none meets the occluder.
  const DVec2 cell = (g.hi - g.lo) / DVec2(g.columns, g.rows);
  auto index = [](double x, uint32_t n) {
    return uint32_t(std::clamp(std::floor(x), 0.0, double(n - 1)));
  };
  const uint32_t i0 = index((lo.x - g.lo.x) / cell.x, g.columns);
  const uint32_t i1 = index((hi.x - g.lo.x) / cell.x, g.columns);
  const uint32_t j0 = index((lo.y - g.lo.y) / cell.y, g.rows);
  const uint32_t j1 = index((hi.y - g.lo.y) / cell.y, g.rows);
  const uint64_t bits =
      (i1 == 63 ? ~uint64_t(0) : (uint64_t(1) << (i1 + 1)) - 1) & ~((uint64_t(1) << i0) - 1);
  bool full = true, partly = false;
  for (uint32_t j = j0; j <= j1; ++j) {
    full &= (g.full[j] & bits) == bits;
    partly |= (g.partly[j] & bits) != 0;
  }
  if (full) return Cover::Hidden;
  return partly ? Cover::Maybe : Cover::Never;
}

struct ShotOccluders {
  std::vector<ShotOccluder> chosen;
  Aabb source;  // where its rays may end, before the margin
  float margin = 0.0f;
  float source_margin = 0.0f;  // how far the source's ray ends may lie outside `source`

  uint32_t every() const {
    return chosen.size() >= kOccluders ? ~0u : (uint32_t(1) << chosen.size()) - 1;
  }

  void add(const Occluder& o, float side) {
    ShotOccluder x;
    x.occluder = &o, x.side = side;
    x.su = corner_coordinates(source, source_margin, o.origin, o.u);
    x.sw = corner_coordinates(source, source_margin, o.origin, o.w);
    x.sd = corner_coordinates(source, source_margin, o.origin, o.normal);
    chosen.push_back(x);
  }

  // Whether one of the occluders in `mask` hides the box; those that can hide nothing inside
  // it are taken out of the mask.
  // `last`, the one that hid the last box hidden (near it, most likely to hide this one), is
  // tried first, and set.
  bool hidden(const Aabb& box, uint32_t& mask, int& last) const {
    if (last >= 0 && (mask >> last & 1u)) {
      const Cover c = covers(chosen[size_t(last)], box, margin);
      if (c == Cover::Hidden) return true;
      if (c == Cover::Never) mask &= ~(uint32_t(1) << last);
    }
    for (uint32_t m = mask & ~(last >= 0 ? uint32_t(1) << last : 0u); m != 0; m &= m - 1) {
      const int k = std::countr_zero(m);
      const Cover c = covers(chosen[size_t(k)], box, margin);
      if (c == Cover::Hidden) {
        last = k;
        return true;
      }
      if (c == Cover::Never) mask &= ~(uint32_t(1) << k);
    }
    return false;
  }
};

}  // namespace

OcclusionCulling make_occlusion_culling(const Hierarchy& h, float shadow_offset) {
  OcclusionCulling c;
  // Shadow rays start up to the shadow offset off a receiving point (moved a 1e-4 fraction of
  // the way to its polygon's centroid: inside the polygon) and end up to it off the source.
  c.rounding = 1e-6 * double(h.bounds.magnitude());
  c.margin = 4.0 * double(shadow_offset) + c.rounding;
  c.occluders = fuse_occluders(h, c.margin);
  if (c.occluders.empty()) return c;
  for (const Occluder& o : c.occluders) c.occluder_boxes.push_back(o.box);
  const Triangles& t = h.triangles;
  std::vector<Aabb> boxes(t.size());
  std::vector<Vec3> centres(t.size());
  for (size_t i = 0; i < t.size(); ++i)
    boxes[i] = triangle_box(t.corners[i]), centres[i] = t.centroid(i);
  c.tree = make_box_tree(boxes, centres, kLeafTriangles);
  c.cullable.resize(c.tree.size());
  for (size_t n = 0; n < c.tree.size(); ++n) {
    uint8_t all = 1;
    for (uint32_t k = c.tree.first[n]; k < c.tree.first[n] + c.tree.count[n]; ++k)
      all &= uint8_t(h.objects[size_t(t.object[c.tree.order[k]])].receives_shadows);
    c.cullable[n] = all;
  }
  return c;
}

namespace {

// The occluders of one shot: those the source lies wholly on one side of and with something of
// the scene behind them, best placed first (by about the solid angle their parts fill seen from
// the source), each kept unless those before it hide it.
ShotOccluders choose_occluders(const OcclusionCulling& c, const ShotSource& src) {
  ShotOccluders so;
  so.margin = float(c.margin);
  // Where the shot's rays may end: one of its fine points each (the one nearest its stratum's
  // power), moved off the surface by less than the margin. Their box lies inside the source's
  // triangles, so a floor that runs up to a wall lies wholly on one side of the wall, as the
  // cluster's box would not; and it is geometry, so a cluster culls the same receivers at every
  // shot and keeps its kept answers (kept_rays.h).
  Aabb ends;
  const SampleLanes& fine = src.fine_sample;
  for (size_t i = 0; i < fine.size(); ++i)
    if (fine.area[i] > 0.0f) ends.extend(fine.point(i));
  if (ends.empty()) ends = src.box;
  so.source = ends;
  // A point or spot light's rays end at its position, not off a surface: only rounding moves
  // them. Grown by the whole margin, a lamp hung less than two margins under a ceiling would see
  // over the top of every wall (the crossings would come within the margin of the walls' top
  // edges); hung more than one, it is now hidden from what lies far beyond a wall near it.
  const bool at_point = src.light >= 0 && src.emitter->kind != LightKind::Directional;
  so.source_margin = float(at_point ? c.rounding : c.margin);
  const DVec3 centre(ends.center()), half(ends.extent() * 0.5f);
  // Beyond the roulette's reach at any height and facing an occluder hides only what the shot
  // skips anyway: the points it reaches lie nearer, and so do the segments to them.
  std::vector<uint32_t> near;
  for (size_t k = 0; k < c.occluder_boxes.size(); ++k)
    if (src.roulette_distance_reaches(c.occluder_boxes[k])) near.push_back(uint32_t(k));
  std::vector<double> score(near.size(), 0.0);
  tbb::parallel_for(size_t(0), near.size(), [&](size_t i) {
    const Occluder& o = c.occluders[near[i]];
    const double d = glm::dot(centre - o.origin, o.normal);
    if (std::abs(d) <= glm::dot(half, glm::abs(o.normal)) + so.source_margin + c.margin) return;
    if (!(o.hides_behind & (d > 0.0 ? 1 : 2))) return;
    double sum = 0.0;
    for (size_t q = 0; q < o.part_area.size(); ++q) {
      const DVec3 to = DVec3(o.part_centre[q]) - centre;
      const double a = double(o.part_area[q]), r2 = glm::dot(to, to) + a;
      sum += a * std::abs(glm::dot(to, o.normal)) / (r2 * std::sqrt(r2));
    }
    score[i] = sum;
  });
  std::vector<std::pair<double, uint32_t>> scored;
  for (size_t i = 0; i < score.size(); ++i)
    if (score[i] > 0.0) scored.push_back({-score[i], near[i]});
  const size_t keep = std::min(scored.size(), kCandidates);
  std::partial_sort(scored.begin(), scored.begin() + long(keep), scored.end());
  for (size_t k = 0; k < keep && so.chosen.size() < kOccluders; ++k) {
    const Occluder& o = c.occluders[scored[k].second];
    uint32_t all = so.every();
    int last = -1;
    if (so.hidden(o.box, all, last)) continue;  // hidden itself: it hides nothing more
    so.add(o, glm::dot(centre - o.origin, o.normal) > 0.0 ? 1.0f : -1.0f);
  }
  return so;
}

// A node still to look at, with the occluders that may hide something inside it.
struct Visit {
  uint32_t node, mask;
};

// Appends the triangles of the subtree at `start` that are not hidden, depth first.
void walk(const OcclusionCulling& c, const ShotSource& src, const ShotOccluders& so, Visit start,
          std::vector<std::pair<uint32_t, uint32_t>>& stack, std::vector<uint32_t>& out) {
  const BoxTree& tree = c.tree;
  // A planar source lights nothing behind its plane (may_receive's test, on whole boxes, with
  // room for the rounding of either test: a box nearly in the plane is left to may_receive).
  const float front = 1e-6f * src.extent - so.margin;
  int last = -1;
  walk_box_tree(
      tree, start.node, start.mask, stack,
      [&](uint32_t node, uint32_t& mask) {
        const Aabb& b = tree.box[node];
        if (!src.roulette_reaches_box(b)) return false;
        if (src.planar && highest_above(b, src.centroid, src.axis) <= front) return false;
        return !(mask != 0 && c.cullable[node] && so.hidden(b, mask, last));
      },
      [&](uint32_t node) {
        const uint32_t first = tree.first[node];
        out.insert(out.end(), tree.order.begin() + first,
                   tree.order.begin() + first + tree.count[node]);
      });
}

}  // namespace

void unhidden_triangles(const OcclusionCulling& c, const ShotSource& src,
                        std::vector<uint32_t>& out) {
  out.clear();
  const BoxTree& tree = c.tree;
  if (tree.box.empty()) return;
  const ShotOccluders so = choose_occluders(c, src);
  // The top of the tree, a few levels down, shared between the threads in order.
  std::vector<Visit> top{{0, so.every()}}, next;
  for (int level = 0; level < 6; ++level) {
    next.clear();
    for (const Visit& v : top) {
      if (tree.leaf(v.node)) {
        next.push_back(v);
      } else {
        next.push_back({v.node + 1, v.mask});
        next.push_back({tree.right[v.node], v.mask});
      }
    }
    top.swap(next);
  }
  std::vector<std::vector<uint32_t>> parts(top.size());
  tbb::parallel_for(size_t(0), top.size(), [&](size_t k) {
    std::vector<std::pair<uint32_t, uint32_t>> stack;
    walk(c, src, so, top[k], stack, parts[k]);
  });
  for (const std::vector<uint32_t>& p : parts) out.insert(out.end(), p.begin(), p.end());
  std::sort(out.begin(), out.end());
}

}  // namespace rad
