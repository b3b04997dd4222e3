#include "solver/occlusion_culling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

#include "hierarchy/triangle_adjacency.h"
#include "solver/shot_source.h"
#include "visibility/agreement.h"

namespace rad {

namespace {

using DVec2 = glm::dvec2;

constexpr uint32_t kLeafTriangles = 8;
// Occluders picked per shot, and how many of the best-placed regions are looked at for them.
constexpr size_t kOccluders = 32;  // one bit each in a mask
constexpr size_t kCandidates = 8 * kOccluders;

uint32_t build_node(ReceiverTree& tree, const Hierarchy& h, const std::vector<Vec3>& centroid,
                    uint32_t first, uint32_t count) {
  const Triangles& t = h.triangles;
  const uint32_t node = uint32_t(tree.box.size());
  Aabb box, centres;
  uint8_t cullable = 1;
  for (uint32_t k = first; k < first + count; ++k) {
    const uint32_t i = tree.order[k];
    box.extend(triangle_box(t.corners[i]));
    centres.extend(centroid[i]);
    cullable &= uint8_t(h.objects[size_t(t.object[i])].receives_shadows);
  }
  tree.box.push_back(box);
  tree.first.push_back(first), tree.count.push_back(count), tree.right.push_back(0);
  tree.cullable.push_back(cullable);
  if (count <= kLeafTriangles) return node;
  const int axis = centres.widest_axis();
  const uint32_t half = count / 2;
  auto begin = tree.order.begin() + first;
  // Ties broken by index: the same scene gives the same tree.
  std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
    return centroid[a][axis] < centroid[b][axis] ||
           (centroid[a][axis] == centroid[b][axis] && a < b);
  });
  build_node(tree, h, centroid, first, half);
  const uint32_t right = build_node(tree, h, centroid, first + half, count - half);
  tree.right[node] = right;
  return node;
}

ReceiverTree make_receiver_tree(const Hierarchy& h) {
  const Triangles& t = h.triangles;
  ReceiverTree tree;
  if (t.size() == 0) return tree;
  tree.order.resize(t.size());
  std::iota(tree.order.begin(), tree.order.end(), 0u);
  std::vector<Vec3> centroid(t.size());
  for (size_t i = 0; i < t.size(); ++i) centroid[i] = t.centroid(i);
  build_node(tree, h, centroid, 0, uint32_t(t.size()));
  return tree;
}

// Area of the convex polygon a[0 .. n).
double polygon_area(const DVec2* a, size_t n) {
  double twice = 0.0;
  for (size_t i = 1; i + 1 < n; ++i) {
    twice += (a[i].x - a[0].x) * (a[i + 1].y - a[0].y) - (a[i + 1].x - a[0].x) * (a[i].y - a[0].y);
  }
  return 0.5 * std::abs(twice);
}

// Area of triangle t inside the convex polygon c[0 .. m) (Sutherland-Hodgman: t clipped by each
// edge of c in turn; either winding).
double area_inside(const std::array<DVec2, 3>& t, const DVec2* c, size_t m) {
  DVec2 a[16], b[16];
  size_t n = 3;
  for (size_t i = 0; i < 3; ++i) a[i] = t[i];
  const double orient =
      (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[2].x - c[0].x) * (c[1].y - c[0].y);
  const double s = orient >= 0.0 ? 1.0 : -1.0;
  for (size_t e = 0; e < m && n > 0; ++e) {
    const DVec2 &p0 = c[e], &p1 = c[(e + 1) % m];
    auto inside = [&](const DVec2& p) {
      return s * ((p1.x - p0.x) * (p.y - p0.y) - (p1.y - p0.y) * (p.x - p0.x));
    };
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      const DVec2 &p = a[i], &q = a[(i + 1) % n];
      const double dp = inside(p), dq = inside(q);
      if (dp >= 0.0) b[k++] = p;
      if ((dp >= 0.0) != (dq >= 0.0)) b[k++] = p + (q - p) * (dp / (dp - dq));
    }
    n = k;
    for (size_t i = 0; i < n; ++i) a[i] = b[i];
  }
  return polygon_area(a, n);
}

double area_in_rect(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi) {
  const DVec2 rect[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  return area_inside(t, rect, 4);
}

// Whether triangle t holds the rectangle [lo, hi] (its four corners).
bool holds(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi) {
  const double orient =
      (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
  const DVec2 q[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (size_t e = 0; e < 3; ++e) {
    const DVec2 &a = t[e], &b = t[(e + 1) % 3];
    for (const DVec2& p : q) {
      if (orient * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) < 0.0) return false;
    }
  }
  return orient != 0.0;
}

std::array<DVec2, 3> flatten(const DVec3& origin, const DVec3& u, const DVec3& w,
                             const std::array<Vec3, 3>& c) {
  std::array<DVec2, 3> t;
  for (size_t k = 0; k < 3; ++k) {
    const DVec3 d = DVec3(c[k]) - origin;
    t[k] = {glm::dot(d, u), glm::dot(d, w)};
  }
  return t;
}

std::array<DVec2, 2> box_of(const std::array<DVec2, 3>& t) {
  return {glm::min(glm::min(t[0], t[1]), t[2]), glm::max(glm::max(t[0], t[1]), t[2])};
}

// Any frame of the plane with unit normal n.
void any_frame(const DVec3& n, DVec3& u, DVec3& w) {
  const DVec3 a = std::abs(n.x) < 0.6 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
  u = glm::normalize(glm::cross(n, a));
  w = glm::cross(n, u);
}

// The occluder of regions `parts` (coplanar, not overlapping), in the frame (one of their edges'
// directions) where their box is smallest: a wall gets its own sides as axes, not a diagonal.
Occluder make_occluder(const std::vector<FlatRegion>& regions, const std::vector<uint32_t>& parts) {
  Occluder o;
  const FlatRegion& first = regions[parts[0]];
  o.normal = DVec3(first.normal), o.origin = DVec3(first.point);
  std::vector<Vec3> points;
  std::vector<DVec3> directions;
  for (uint32_t r : parts) {
    for (const auto& c : regions[r].triangles) {
      for (size_t k = 0; k < 3; ++k) {
        points.push_back(c[k]);
        directions.push_back(DVec3(c[(k + 1) % 3]) - DVec3(c[k]));
      }
    }
    o.part_centre.push_back(Vec3(0.0f));
    o.part_area.push_back(regions[r].area);
  }
  any_frame(o.normal, o.u, o.w);
  // The distinct edge directions (a fused wall repeats its pieces' few), longest edges first.
  std::sort(directions.begin(), directions.end(),
            [](const DVec3& a, const DVec3& b) { return glm::length(a) > glm::length(b); });
  std::vector<DVec3> distinct;
  for (DVec3 d : directions) {
    d -= o.normal * glm::dot(d, o.normal);
    if (!(glm::length(d) > 0.0)) continue;
    d = glm::normalize(d);
    bool seen = false;
    for (const DVec3& e : distinct) seen |= std::abs(glm::dot(d, e)) > 1.0 - 1e-9;
    if (!seen) distinct.push_back(d);
    if (distinct.size() == 16) break;
  }
  double best = std::numeric_limits<double>::infinity();
  for (const DVec3& u : distinct) {
    const DVec3 w = glm::cross(o.normal, u);
    DVec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const Vec3& p : points) {
      const DVec2 q(glm::dot(DVec3(p), u), glm::dot(DVec3(p), w));
      lo = glm::min(lo, q), hi = glm::max(hi, q);
    }
    const double area = (hi.x - lo.x) * (hi.y - lo.y);
    if (area < best) best = area, o.u = u, o.w = w;
  }
  o.lo = DVec2(std::numeric_limits<double>::infinity()), o.hi = -o.lo;
  std::vector<std::array<DVec2, 3>> tris;
  std::vector<std::array<DVec2, 2>> boxes;
  for (size_t k = 0; k < parts.size(); ++k) {
    const FlatRegion& r = regions[parts[k]];
    Aabb part;
    for (const auto& c : r.triangles) {
      for (const Vec3& p : c) part.extend(p);
      tris.push_back(flatten(o.origin, o.u, o.w, c));
      boxes.push_back(box_of(tris.back()));
      o.lo = glm::min(o.lo, boxes.back()[0]), o.hi = glm::max(o.hi, boxes.back()[1]);
    }
    o.part_centre[k] = part.center();
    o.box.extend(part);
  }
  // Square-ish cells, 64 along the longer side.
  const DVec2 size = o.hi - o.lo;
  const double longer = std::max(size.x, size.y);
  auto cells = [&](double side) {
    return uint32_t(std::clamp(std::ceil(64.0 * side / longer), 1.0, 64.0));
  };
  o.columns = longer > 0.0 ? cells(size.x) : 1, o.rows = longer > 0.0 ? cells(size.y) : 1;
  o.full.assign(o.rows, 0), o.partly.assign(o.rows, 0);
  const DVec2 cell = size / DVec2(o.columns, o.rows);
  for (uint32_t j = 0; j < o.rows; ++j) {
    for (uint32_t i = 0; i < o.columns; ++i) {
      const DVec2 lo = o.lo + cell * DVec2(i, j), hi = lo + cell;
      double covered = 0.0;
      bool whole = false;
      for (size_t k = 0; k < tris.size() && !whole; ++k) {
        const auto& b = boxes[k];
        if (b[1].x <= lo.x || b[0].x >= hi.x || b[1].y <= lo.y || b[0].y >= hi.y) continue;
        whole = holds(tris[k], lo, hi);
        covered += whole ? 0.0 : area_in_rect(tris[k], lo, hi);
      }
      const double need = cell.x * cell.y;
      if (whole || covered >= need * (1.0 - 1e-6)) o.full[j] |= uint64_t(1) << i;
      if (whole || covered > 0.0) o.partly[j] |= uint64_t(1) << i;
    }
  }
  return o;
}

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

  uint32_t every() const {
    return chosen.size() >= kOccluders ? ~0u : (uint32_t(1) << chosen.size()) - 1;
  }

  void add(const Occluder& o, float side) {
    ShotOccluder x;
    x.occluder = &o, x.side = side;
    x.su = corner_coordinates(source, margin, o.origin, o.u);
    x.sw = corner_coordinates(source, margin, o.origin, o.w);
    x.sd = corner_coordinates(source, margin, o.origin, o.normal);
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

// Union-find over regions.
uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

bool touch(const Aabb& a, const Aabb& b, float gap) {
  return a.lo.x <= b.hi.x + gap && b.lo.x <= a.hi.x + gap && a.lo.y <= b.hi.y + gap &&
         b.lo.y <= a.hi.y + gap && a.lo.z <= b.hi.z + gap && b.lo.z <= a.hi.z + gap;
}

// A fused occluder stays within this many triangles: each coverage test looks at them all.
constexpr size_t kMaxFused = 32;

}  // namespace

OcclusionCulling make_occlusion_culling(const Hierarchy& h, float shadow_offset) {
  OcclusionCulling c;
  // Shadow rays start up to the shadow offset off a receiving point (moved a 1e-4 fraction of
  // the way to its polygon's centroid: inside the polygon) and end up to it off the source.
  c.margin = 4.0 * double(shadow_offset) + 1e-6 * double(h.bounds.magnitude());
  std::vector<FlatRegion> regions;
  for (FlatRegion& r : flat_regions(h))
    if (h.objects[size_t(r.object)].casts_shadows) regions.push_back(std::move(r));
  if (regions.empty()) return c;
  std::vector<Aabb> box(regions.size());
  for (size_t r = 0; r < regions.size(); ++r)
    for (const auto& t : regions[r].triangles) box[r].extend(triangle_box(t));
  // Regions by plane (normal and offset rounded; a plane split by the rounding is only fused
  // less), then along x: touching coplanar regions are neighbours in this order.
  const double step = 16.0 * c.margin;
  auto key = [&](uint32_t r) {
    const Vec3 n = regions[r].normal;
    return std::array<int64_t, 5>{std::llround(double(n.x) * 1e3), std::llround(double(n.y) * 1e3),
                                  std::llround(double(n.z) * 1e3),
                                  std::llround(double(glm::dot(n, regions[r].point)) / step), 0};
  };
  std::vector<uint32_t> order(regions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<std::array<int64_t, 5>> keys(regions.size());
  for (uint32_t r = 0; r < regions.size(); ++r) keys[r] = key(r);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (keys[a] != keys[b]) return keys[a] < keys[b];
    return box[a].lo.x < box[b].lo.x || (box[a].lo.x == box[b].lo.x && a < b);
  });
  std::vector<uint32_t> parent(regions.size()), size(regions.size());
  std::vector<std::vector<uint32_t>> members(regions.size());
  for (uint32_t r = 0; r < regions.size(); ++r) {
    parent[r] = r, members[r] = {r};
    size[r] = uint32_t(regions[r].triangles.size());
  }
  const float gap = float(c.margin);
  const double tolerance = ambiguity_limit(h);
  for (size_t i = 0; i < order.size(); ++i) {
    const uint32_t a = order[i];
    const DVec3 n(regions[a].normal);
    DVec3 u, w;
    any_frame(n, u, w);
    for (size_t j = i + 1;
         j < order.size() && keys[order[j]] == keys[a] && box[order[j]].lo.x <= box[a].hi.x + gap;
         ++j) {
      const uint32_t b = order[j];
      if (!touch(box[a], box[b], gap)) continue;
      if (glm::dot(n, DVec3(regions[b].normal)) < double(kPlanarCos) ||
          std::abs(glm::dot(n, DVec3(regions[b].point) - DVec3(regions[a].point))) > c.margin)
        continue;
      const uint32_t ra = root(parent, a), rb = root(parent, b);
      if (ra == rb || size[ra] + size[rb] > kMaxFused) continue;
      // Every corner of both within the ambiguity distance of the plane the fused occluder will
      // have (its lowest region's, which is the set's root): a slit between two pieces a step
      // apart, or a ray past a tilted piece's edge, is then one the backends may disagree on.
      const uint32_t keep = std::min(ra, rb);
      const DVec3 kn(regions[keep].normal), kp(regions[keep].point);
      bool flat = true;
      for (const uint32_t set : {ra, rb}) {
        for (uint32_t x : members[set]) {
          for (const auto& t : regions[x].triangles) {
            for (const Vec3& q : t) flat &= std::abs(glm::dot(DVec3(q) - kp, kn)) <= tolerance;
          }
        }
      }
      if (!flat) continue;
      // The two sets must not overlap (coincident duplicates would count twice).
      bool overlaps = false;
      for (uint32_t x : members[ra]) {
        for (uint32_t y : members[rb]) {
          if (!touch(box[x], box[y], 0.0f)) continue;
          for (const auto& tx : regions[x].triangles) {
            const auto fx = flatten(DVec3(regions[a].point), u, w, tx);
            for (const auto& ty : regions[y].triangles) {
              const auto fy = flatten(DVec3(regions[a].point), u, w, ty);
              if (area_inside(fx, fy.data(), 3) >
                  1e-7 * double(std::min(regions[x].area, regions[y].area)))
                overlaps = true;
            }
          }
        }
      }
      if (overlaps) continue;
      const uint32_t gone = std::max(ra, rb);
      parent[gone] = keep;
      size[keep] += size[gone];
      members[keep].insert(members[keep].end(), members[gone].begin(), members[gone].end());
      members[gone].clear();
    }
  }
  std::vector<uint32_t> roots;
  for (uint32_t r = 0; r < regions.size(); ++r) {
    if (root(parent, r) != r) continue;
    std::sort(members[r].begin(), members[r].end());
    roots.push_back(r);
  }
  c.occluders.resize(roots.size());
  tbb::parallel_for(size_t(0), roots.size(), [&](size_t k) {
    Occluder o = make_occluder(regions, members[roots[k]]);
    const double mid = glm::dot(DVec3(h.bounds.center()) - o.origin, o.normal);
    const double reach = glm::dot(DVec3(h.bounds.extent()) * 0.5, glm::abs(o.normal));
    o.hides_behind = uint8_t((mid - reach < -c.margin ? 1 : 0) | (mid + reach > c.margin ? 2 : 0));
    c.occluders[k] = std::move(o);
  });
  for (const Occluder& o : c.occluders) c.occluder_boxes.push_back(o.box);
  c.tree = make_receiver_tree(h);
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
    if (std::abs(d) <= glm::dot(half, glm::abs(o.normal)) + 2.0 * c.margin) return;
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
          std::vector<Visit>& stack, std::vector<uint32_t>& out) {
  const ReceiverTree& tree = c.tree;
  // A planar source lights nothing behind its plane (may_receive's test, on whole boxes, with
  // room for the rounding of either test: a box nearly in the plane is left to may_receive).
  const float front = 1e-6f * src.extent - so.margin;
  stack.assign(1, start);
  int last = -1;
  while (!stack.empty()) {
    Visit v = stack.back();
    stack.pop_back();
    const Aabb& b = tree.box[v.node];
    if (!src.roulette_reaches_box(b)) continue;
    if (src.planar && highest_above(b, src.centroid, src.axis) <= front) continue;
    if (v.mask != 0 && tree.cullable[v.node] && so.hidden(b, v.mask, last)) continue;
    if (tree.leaf(v.node)) {
      const uint32_t first = tree.first[v.node];
      out.insert(out.end(), tree.order.begin() + first,
                 tree.order.begin() + first + tree.count[v.node]);
    } else {
      stack.push_back({tree.right[v.node], v.mask});
      stack.push_back({v.node + 1, v.mask});
    }
  }
}

}  // namespace

void unhidden_triangles(const OcclusionCulling& c, const ShotSource& src,
                        std::vector<uint32_t>& out) {
  out.clear();
  const ReceiverTree& tree = c.tree;
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
    std::vector<Visit> stack;
    walk(c, src, so, top[k], stack, parts[k]);
  });
  for (const std::vector<uint32_t>& p : parts) out.insert(out.end(), p.begin(), p.end());
  std::sort(out.begin(), out.end());
}

}  // namespace rad
