#include "solver/clusters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <tuple>

#include "hierarchy/triangle_adjacency.h"
#include "visibility/agreement.h"

namespace rad {

namespace {

// Normals within 0.1 degree (kPlanarCos) make a planar cluster (the Cornell box's red wall, folded
// by 0.47 degrees, gained 2.7% more than it shot when taken as planar); a face cluster's normals
// are within 25 degrees of its seed's (Willmott et al. bound the cone too; 25 keeps a sphere's
// cluster a cap whose outline contour is seen from the front by most receivers).
const float kCurvedCos = std::cos(25.0f * 3.14159265f / 180.0f);

// Splits tris (one region) in two along its box's longest axis until every part's area is
// within max_area. The cut is put on a vertex coordinate near the median centroid when one
// lies strictly inside the centroids' range, so a tessellated grid splits along a grid line and
// the parts' outlines stay straight.
void split_region(const Triangles& t, std::vector<uint32_t> tris, double max_area,
                  std::vector<std::vector<uint32_t>>& parts) {
  Aabb box;
  double area = 0.0;
  for (uint32_t i : tris) {
    area += double(t.area[i]);
    for (const Vec3& p : t.corners[i]) box.extend(p);
  }
  if (tris.size() == 1 || area <= max_area) {
    parts.push_back(std::move(tris));
    return;
  }
  const int axis = box.widest_axis();
  std::sort(tris.begin(), tris.end(), [&](uint32_t a, uint32_t b) {
    const float ca = t.centroid(a)[axis], cb = t.centroid(b)[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const float lo = t.centroid(tris.front())[axis], hi = t.centroid(tris.back())[axis];
  const float median = t.centroid(tris[tris.size() / 2])[axis];
  float cut = median, best = std::numeric_limits<float>::infinity();
  for (uint32_t i : tris) {
    for (const Vec3& p : t.corners[i]) {
      const float c = p[axis];
      if (c > lo && c < hi && std::abs(c - median) < best) best = std::abs(c - median), cut = c;
    }
  }
  size_t mid = size_t(std::partition_point(tris.begin(), tris.end(),
                                           [&](uint32_t i) { return t.centroid(i)[axis] < cut; }) -
                      tris.begin());
  if (mid == 0 || mid == tris.size()) mid = tris.size() / 2;
  split_region(t, std::vector<uint32_t>(tris.begin(), tris.begin() + long(mid)), max_area, parts);
  split_region(t, std::vector<uint32_t>(tris.begin() + long(mid), tris.end()), max_area, parts);
}

// The corners of a cluster's triangles that lie on no boundary edge, once each.
void interior_vertices(const Triangles& t, const std::vector<std::array<uint32_t, 3>>& v,
                       const std::vector<uint32_t>& tris, const std::vector<BoundaryEdge>& bnd,
                       std::vector<Vec3>& out) {
  std::vector<uint32_t> on_boundary;
  for (const BoundaryEdge& d : bnd) on_boundary.push_back(d.a), on_boundary.push_back(d.b);
  std::sort(on_boundary.begin(), on_boundary.end());
  std::vector<std::pair<uint32_t, Vec3>> inner;
  for (uint32_t i : tris) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t id = v[i][size_t(k)];
      if (!std::binary_search(on_boundary.begin(), on_boundary.end(), id))
        inner.emplace_back(id, t.corners[i][size_t(k)]);
    }
  }
  std::sort(inner.begin(), inner.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < inner.size(); ++i)
    if (i == 0 || inner[i].first != inner[i - 1].first) out.push_back(inner[i].second);
}

}  // namespace

Clusters make_clusters(const Hierarchy& h, double max_area) {
  const Triangles& t = h.triangles;
  // One pass of region growing with the face clusters' cone; a region whose normals all agree
  // within 0.1 degree is planar. (Growing planar regions first fragments a finely tessellated
  // sphere, whose neighbouring quads lie within a degree of each other, into thousands.)
  const Regions found = find_regions(t, kCurvedCos);
  const double tolerance = ambiguity_limit(h);  // rounding of the scene's coordinates
  const std::vector<std::array<uint32_t, 3>>& v = found.corners;
  const std::vector<uint32_t>& flat = found.triangles;
  const std::vector<uint32_t>& starts = found.first;
  std::vector<std::vector<uint32_t>> regions;
  std::vector<uint8_t> region_planar;
  for (size_t r = 0; r + 1 < starts.size(); ++r) {
    regions.emplace_back(flat.begin() + starts[r], flat.begin() + starts[r + 1]);
    bool planar = true;
    for (uint32_t i : regions.back())
      planar &= glm::dot(t.normal[i], t.normal[flat[starts[r]]]) >= kPlanarCos;
    region_planar.push_back(planar);
  }
  // Regions in order of their lowest triangle, so cluster ids follow the scene.
  std::vector<size_t> order(regions.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return *std::min_element(regions[a].begin(), regions[a].end()) <
           *std::min_element(regions[b].begin(), regions[b].end());
  });

  Clusters k;
  k.cluster_of.assign(t.size(), 0);
  k.first.push_back(0);
  k.edge_first.push_back(0);
  k.interior_first.push_back(0);
  std::vector<std::vector<uint32_t>> parts;
  for (size_t r : order) {
    parts.clear();
    split_region(t, regions[r], max_area, parts);
    for (std::vector<uint32_t>& tris : parts) {
      std::sort(tris.begin(), tris.end());
      const uint32_t c = uint32_t(k.size());
      double area = 0.0;
      DVec3 centre(0.0), normal(0.0);
      Aabb box;
      for (uint32_t i : tris) {
        k.polygons.push_back(i);
        k.cluster_of[i] = c;
        area += double(t.area[i]);
        centre += DVec3(t.centroid(i)) * double(t.area[i]);
        normal += DVec3(t.normal[i]) * double(t.area[i]);
        for (const Vec3& p : t.corners[i]) box.extend(p);
      }
      const Vec3 centroid(centre / area);
      Vec3 axis(glm::normalize(normal));
      if (!(glm::length(axis) > 0.5f)) axis = t.normal[tris.front()];
      float cone = 1.0f, lo = 0.0f, hi = 0.0f;
      for (uint32_t i : tris) {
        cone = std::min(cone, glm::dot(axis, t.normal[i]));
        const float off = glm::dot(centroid - t.corners[i][0], t.normal[i]);
        lo = std::min(lo, off), hi = std::max(hi, off);
      }
      const bool planar = region_planar[r] || tris.size() == 1;
      k.first.push_back(uint32_t(k.polygons.size()));
      const std::vector<BoundaryEdge> bnd = boundary_edges(t, v, tris);
      outline(bnd, tolerance, k.edge_a, k.edge_b);
      if (!planar) interior_vertices(t, v, tris, bnd, k.interior);
      k.interior_first.push_back(uint32_t(k.interior.size()));
      k.edge_first.push_back(uint32_t(k.edge_a.size()));
      k.centroid.push_back(centroid);
      k.axis.push_back(axis);
      k.area.push_back(float(area));
      k.extent.push_back(box.diagonal());
      k.box.push_back(box);
      cone = std::clamp(cone, -1.0f, 1.0f);
      k.cone_cos.push_back(planar ? 1.0f : cone);
      k.cone_sin.push_back(planar ? 0.0f : std::sqrt(1.0f - cone * cone));
      k.offset_lo.push_back(planar ? 0.0f : lo);
      k.offset_hi.push_back(planar ? 0.0f : hi);
      k.planar.push_back(planar);
    }
  }
  return k;
}

}  // namespace rad
