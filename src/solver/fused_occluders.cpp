#include "solver/fused_occluders.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/planar_geometry.h"
#include "hierarchy/triangle_adjacency.h"
#include "visibility/agreement.h"
#include "visibility/occluders.h"

namespace rad {

namespace {

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
  plane_frame(o.normal, o.u, o.w);
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
      tris.push_back(flatten_triangle(o.origin, o.u, o.w, c));
      boxes.push_back(bounds_2d(tris.back()));
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
        whole = triangle_holds_rect(tris[k], lo, hi);
        covered += whole ? 0.0 : triangle_area_in_rect(tris[k], lo, hi);
      }
      const double need = cell.x * cell.y;
      if (whole || covered >= need * (1.0 - 1e-6)) o.full[j] |= uint64_t(1) << i;
      if (whole || covered > 0.0) o.partly[j] |= uint64_t(1) << i;
    }
  }
  return o;
}

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

std::vector<Occluder> fuse_occluders(const Hierarchy& h, double margin) {
  std::vector<FlatRegion> regions;
  for (FlatRegion& r : flat_regions(h))
    // A cut-out hides nothing wholly: light passes its holes.
    if (h.objects[size_t(r.object)].casts_shadows && !h.objects[size_t(r.object)].cutout)
      regions.push_back(std::move(r));
  if (regions.empty()) return {};
  std::vector<Aabb> box(regions.size());
  for (size_t r = 0; r < regions.size(); ++r)
    for (const auto& t : regions[r].triangles) box[r].extend(triangle_box(t));
  // Regions by plane (normal and offset rounded; a plane split by the rounding is only fused
  // less), then along x: touching coplanar regions are neighbours in this order.
  const double step = 16.0 * margin;
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
  const float gap = float(margin);
  const double tolerance = ambiguity_limit(h);
  for (size_t i = 0; i < order.size(); ++i) {
    const uint32_t a = order[i];
    const DVec3 n(regions[a].normal);
    DVec3 u, w;
    plane_frame(n, u, w);
    for (size_t j = i + 1;
         j < order.size() && keys[order[j]] == keys[a] && box[order[j]].lo.x <= box[a].hi.x + gap;
         ++j) {
      const uint32_t b = order[j];
      if (!touch(box[a], box[b], gap)) continue;
      if (glm::dot(n, DVec3(regions[b].normal)) < double(kPlanarCos) ||
          std::abs(glm::dot(n, DVec3(regions[b].point) - DVec3(regions[a].point))) > margin)
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
            const auto fx = flatten_triangle(DVec3(regions[a].point), u, w, tx);
            for (const auto& ty : regions[y].triangles) {
              const auto fy = flatten_triangle(DVec3(regions[a].point), u, w, ty);
              if (triangle_area_inside(fx, fy.data(), 3) >
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
  std::vector<Occluder> occluders(roots.size());
  tbb::parallel_for(size_t(0), roots.size(), [&](size_t k) {
    Occluder o = make_occluder(regions, members[roots[k]]);
    const double mid = glm::dot(DVec3(h.bounds.center()) - o.origin, o.normal);
    const double reach = glm::dot(DVec3(h.bounds.extent()) * 0.5, glm::abs(o.normal));
    o.hides_behind = uint8_t((mid - reach < -margin ? 1 : 0) | (mid + reach > margin ? 2 : 0));
    occluders[k] = std::move(o);
  });
  return occluders;
}

}  // namespace rad
