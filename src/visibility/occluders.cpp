#include "visibility/occluders.h"

#include <algorithm>
#include <cmath>

#include "hierarchy/triangle_adjacency.h"
#include "visibility/agreement.h"

namespace rad {

namespace {

// Loops longer than this are left as they are (ear clipping is cubic in the loop at worst).
constexpr size_t kMaxLoop = 512;

// The closed loop the outline edges make, as its corners in order, or empty when they make
// anything else (several loops, a corner visited twice).
std::vector<Vec3> single_loop(const std::vector<Vec3>& ea, const std::vector<Vec3>& eb) {
  const size_t n = ea.size();
  if (n < 3 || n > kMaxLoop) return {};
  auto less = [](const Vec3& a, const Vec3& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  };
  std::vector<size_t> by_start(n);
  for (size_t i = 0; i < n; ++i) by_start[i] = i;
  std::sort(by_start.begin(), by_start.end(),
            [&](size_t a, size_t b) { return less(ea[a], ea[b]); });
  for (size_t i = 1; i < n; ++i)
    if (ea[by_start[i]] == ea[by_start[i - 1]]) return {};  // a corner with two edges out
  std::vector<Vec3> loop;
  size_t e = 0;
  for (size_t k = 0; k < n; ++k) {
    loop.push_back(ea[e]);
    auto it = std::lower_bound(by_start.begin(), by_start.end(), eb[e],
                               [&](size_t i, const Vec3& p) { return less(ea[i], p); });
    if (it == by_start.end() || ea[*it] != eb[e]) return {};
    e = *it;
    if (e == 0 && k + 1 < n) return {};  // closed early: more than one loop
  }
  if (e != 0) return {};
  return loop;
}

// Ear clipping of a simple polygon given by its corners in order, in the plane of `normal`
// (its winding around normal is kept; outline() has dropped the corners where it runs
// straight on); appends the triangles to out. False when no ear is found (the loop is not
// simple).
bool clip_ears(std::vector<Vec3> loop, const DVec3& normal, std::vector<std::array<Vec3, 3>>& out) {
  // Projected on the axis plane where the normal is largest, signed so the loop turns left.
  const DVec3 an = glm::abs(normal);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  const int u = (drop + 1) % 3, w = (drop + 2) % 3;
  const double sign = normal[drop] > 0.0 ? 1.0 : -1.0;
  auto cross = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    return sign * ((double(b[u]) - a[u]) * (double(c[w]) - a[w]) -
                   (double(b[w]) - a[w]) * (double(c[u]) - a[u]));
  };
  double size = 0.0;
  for (const Vec3& p : loop) size = std::max(size, double(glm::length(p - loop[0])));
  const double eps = 1e-9 * size * size;
  while (loop.size() > 3) {
    const size_t m = loop.size();
    bool clipped = false;
    for (size_t i = 0; i < m && !clipped; ++i) {
      const Vec3 &a = loop[(i + m - 1) % m], &b = loop[i], &c = loop[(i + 1) % m];
      if (cross(a, b, c) <= eps) continue;  // reflex
      bool empty = true;
      for (size_t j = 0; j < m && empty; ++j) {
        if (j == i || j == (i + 1) % m || j == (i + m - 1) % m) continue;
        const Vec3& p = loop[j];
        empty = !(cross(a, b, p) >= -eps && cross(b, c, p) >= -eps && cross(c, a, p) >= -eps);
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      loop.erase(loop.begin() + long(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (loop.size() == 3) {
    if (cross(loop[0], loop[1], loop[2]) <= eps) return false;
    out.push_back({loop[0], loop[1], loop[2]});
  }
  return true;
}

// Region `tris` as triangles that cover exactly its surface without overlapping: its own one or
// two, or its single loop's ear clipping (checked to cover the same area: no hole, fold or
// overlap the loop alone would miss); nothing when its corners are not in one plane or it has
// more than two triangles and no such loop.
std::optional<FlatRegion> region_surface(const Hierarchy& h,
                                         const std::vector<std::array<uint32_t, 3>>& v,
                                         const std::vector<uint32_t>& tris) {
  const Triangles& t = h.triangles;
  DVec3 normal(0.0);
  double area = 0.0;
  for (uint32_t i : tris) {
    normal += DVec3(t.normal[i]) * double(t.area[i]);
    area += double(t.area[i]);
  }
  if (!(glm::length(normal) > 0.0)) return std::nullopt;
  normal = glm::normalize(normal);
  // Every corner in one plane, within the distance below which the backends may disagree anyway.
  const DVec3 origin(t.corners[tris[0]][0]);
  const double tolerance = ambiguity_limit(h);
  for (uint32_t i : tris)
    for (const Vec3& p : t.corners[i])
      if (std::abs(glm::dot(DVec3(p) - origin, normal)) > tolerance) return std::nullopt;
  FlatRegion r;
  r.normal = Vec3(normal), r.point = Vec3(origin), r.area = float(area);
  r.object = t.object[tris[0]];
  if (tris.size() < 3) {
    // One triangle, or two on either side of their shared edge: they cannot overlap.
    for (uint32_t i : tris) r.triangles.push_back(t.corners[i]);
    return r;
  }
  std::vector<Vec3> ea, eb;
  outline(boundary_edges(t, v, tris), tolerance, ea, eb);
  const std::vector<Vec3> loop = single_loop(ea, eb);
  if (loop.empty() || !clip_ears(loop, normal, r.triangles)) return std::nullopt;
  double merged = 0.0;
  for (const auto& c : r.triangles)
    merged += 0.5 * glm::length(glm::cross(DVec3(c[1]) - DVec3(c[0]), DVec3(c[2]) - DVec3(c[0])));
  if (!(std::abs(merged - area) <= 1e-5 * area)) return std::nullopt;
  return r;
}

}  // namespace

std::optional<Hierarchy> merge_flat_regions(const Hierarchy& h) {
  const Triangles& t = h.triangles;
  const Regions found = find_regions(t, kPlanarCos);
  const std::vector<std::array<uint32_t, 3>>& v = found.corners;
  const std::vector<uint32_t>& flat = found.triangles;
  const std::vector<uint32_t>& starts = found.first;

  // Per triangle: the region it was merged into (its replacement goes where the region's
  // lowest triangle, its seed and first, was, which keeps every object's triangles
  // contiguous), or -1.
  std::vector<int32_t> merged_into(t.size(), -1);
  std::vector<uint32_t> lowest;
  std::vector<std::vector<std::array<Vec3, 3>>> replacement;
  std::vector<uint32_t> tris;
  for (size_t r = 0; r + 1 < starts.size(); ++r) {
    tris.assign(flat.begin() + starts[r], flat.begin() + starts[r + 1]);
    if (tris.size() < 3) continue;
    // A cut-out keeps its triangles: their texture coordinates say where its holes are.
    if (h.objects[size_t(t.object[tris.front()])].cutout) continue;
    std::optional<FlatRegion> surface = region_surface(h, v, tris);
    if (!surface || surface->triangles.size() >= tris.size()) continue;
    std::vector<std::array<Vec3, 3>> out = std::move(surface->triangles);
    for (uint32_t i : tris) merged_into[i] = int32_t(replacement.size());
    lowest.push_back(tris.front());
    replacement.push_back(std::move(out));
  }
  if (replacement.empty()) return std::nullopt;

  Hierarchy m;
  m.scene_name = h.scene_name, m.source_path = h.source_path;
  m.objects = h.objects, m.roots = h.roots;
  m.bounds = h.bounds, m.dropped_degenerate = h.dropped_degenerate;
  std::vector<uint32_t> new_start(t.size() + 1, 0);
  Triangles& out = m.triangles;
  auto add = [&](const std::array<Vec3, 3>& c, const Vec3& normal, float area, int32_t object,
                 const std::array<Vec2, 3>& uv) {
    if (!t.uv.empty()) out.uv.push_back(uv);
    out.corners.push_back(c);
    out.normal.push_back(normal);
    out.area.push_back(area);
    out.object.push_back(object);
  };
  for (size_t i = 0; i < t.size(); ++i) {
    new_start[i] = uint32_t(out.size());
    const int32_t r = merged_into[i];
    if (r < 0) {
      add(t.corners[i], t.normal[i], t.area[i], t.object[i],
          t.uv.empty() ? kNoTextureCoordinates : t.uv[i]);
    } else if (lowest[size_t(r)] == i) {
      for (const auto& c : replacement[size_t(r)]) {
        const Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
        add(c, glm::normalize(n), 0.5f * glm::length(n), t.object[i], kNoTextureCoordinates);
      }
    }
  }
  new_start[t.size()] = uint32_t(out.size());
  for (SceneObject& o : m.objects) {
    const uint32_t end = o.first_triangle + o.triangle_count;
    o.first_triangle = new_start[o.first_triangle];
    o.triangle_count = new_start[end] - o.first_triangle;
    for (TriangleRange& l : o.lit) {
      const uint32_t lit_end = l.first + l.count;
      l.first = new_start[l.first];
      l.count = new_start[lit_end] - l.first;
    }
  }
  return m;
}

std::vector<FlatRegion> flat_regions(const Hierarchy& h) {
  const Regions found = find_regions(h.triangles, kPlanarCos);
  std::vector<FlatRegion> out;
  std::vector<uint32_t> tris;
  for (size_t r = 0; r < found.size(); ++r) {
    tris.assign(found.triangles.begin() + found.first[r],
                found.triangles.begin() + found.first[r + 1]);
    std::optional<FlatRegion> surface = region_surface(h, found.corners, tris);
    if (surface) out.push_back(std::move(*surface));
  }
  return out;
}

}  // namespace rad
