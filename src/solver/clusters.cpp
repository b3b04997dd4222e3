#include "solver/clusters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <tuple>

namespace rad {

namespace {

// Normals within 0.1 degree make a planar cluster (the Cornell box's red wall, folded by 0.47
// degrees, gained 2.7% more than it shot when taken as planar); a face cluster's normals are
// within 25 degrees of its seed's (Willmott et al. bound the cone too; 25 keeps a sphere's
// cluster a cap whose outline contour is seen from the front by most receivers).
const float kPlanarCos = std::cos(0.1f * 3.14159265f / 180.0f);
const float kCurvedCos = std::cos(25.0f * 3.14159265f / 180.0f);

// Corners welded by exact position within each Pure: vertex ids per triangle corner.
std::vector<std::array<uint32_t, 3>> weld(const Triangles& t) {
  struct Key {
    int32_t object;
    uint32_t x, y, z;
    uint32_t corner;  // 3 * triangle + k
  };
  std::vector<Key> keys(t.size() * 3);
  for (size_t i = 0; i < t.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      Key& key = keys[3 * i + size_t(k)];
      key.object = t.object[i];
      const Vec3 p = t.corners[i][size_t(k)] + Vec3(0.0f);  // -0 and +0 weld
      std::memcpy(&key.x, &p.x, 4), std::memcpy(&key.y, &p.y, 4), std::memcpy(&key.z, &p.z, 4);
      key.corner = uint32_t(3 * i + size_t(k));
    }
  }
  auto tie = [](const Key& a) { return std::make_tuple(a.object, a.x, a.y, a.z, a.corner); };
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) { return tie(a) < tie(b); });
  std::vector<std::array<uint32_t, 3>> out(t.size());
  uint32_t id = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 && (keys[i].object != keys[i - 1].object || keys[i].x != keys[i - 1].x ||
                  keys[i].y != keys[i - 1].y || keys[i].z != keys[i - 1].z)) {
      ++id;
    }
    out[keys[i].corner / 3][keys[i].corner % 3] = id;
  }
  return out;
}

// The triangle across each edge (k, k+1) of every triangle, or -1: manifold edges only (used by
// exactly two triangles, in opposite directions).
std::vector<std::array<int32_t, 3>> neighbours(const std::vector<std::array<uint32_t, 3>>& v) {
  struct Edge {
    uint32_t lo, hi, tri, k;
  };
  std::vector<Edge> edges;
  edges.reserve(v.size() * 3);
  for (size_t i = 0; i < v.size(); ++i) {
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = v[i][k], b = v[i][(k + 1) % 3];
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b), uint32_t(i), k});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    return std::tie(a.lo, a.hi, a.tri, a.k) < std::tie(b.lo, b.hi, b.tri, b.k);
  });
  std::vector<std::array<int32_t, 3>> out(v.size(), {-1, -1, -1});
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i == 2) {
      const Edge &e = edges[i], &f = edges[i + 1];
      const bool opposite = v[e.tri][e.k] == v[f.tri][(f.k + 1) % 3];
      if (opposite) out[e.tri][e.k] = int32_t(f.tri), out[f.tri][f.k] = int32_t(e.tri);
    }
    i = j;
  }
  return out;
}

// Edge-connected regions of one Pure grown breadth-first from the lowest unassigned triangle,
// taking neighbours whose normal is within `cos_limit` of the seed's, over the triangles with
// free[i] set. Regions in `out`, flat, with their starts.
void grow_regions(const Triangles& t, const std::vector<std::array<int32_t, 3>>& nb,
                  float cos_limit, std::vector<uint8_t>& free, std::vector<uint32_t>& out,
                  std::vector<uint32_t>& starts) {
  std::vector<uint32_t> queue;
  for (uint32_t seed = 0; seed < t.size(); ++seed) {
    if (!free[seed]) continue;
    starts.push_back(uint32_t(out.size()));
    free[seed] = 0;
    queue.assign(1, seed);
    for (size_t q = 0; q < queue.size(); ++q) {
      const uint32_t i = queue[q];
      out.push_back(i);
      for (int32_t j : nb[i]) {
        if (j < 0 || !free[size_t(j)] || t.object[size_t(j)] != t.object[seed]) continue;
        if (glm::dot(t.normal[size_t(j)], t.normal[seed]) < cos_limit) continue;
        free[size_t(j)] = 0;
        queue.push_back(uint32_t(j));
      }
    }
  }
}

// Splits tris (one region) in two along its box's longest axis until every part's box diagonal
// is within max_extent. The cut is put on a vertex coordinate near the median centroid when one
// lies strictly inside the centroids' range, so a tessellated grid splits along a grid line and
// the parts' outlines stay straight.
void split_region(const Triangles& t, std::vector<uint32_t> tris, float max_extent,
                  std::vector<std::vector<uint32_t>>& parts) {
  Aabb box;
  for (uint32_t i : tris)
    for (const Vec3& p : t.corners[i]) box.extend(p);
  if (tris.size() == 1 || box.diagonal() <= max_extent) {
    parts.push_back(std::move(tris));
    return;
  }
  const Vec3 e = box.extent();
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
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
  split_region(t, std::vector<uint32_t>(tris.begin(), tris.begin() + long(mid)), max_extent, parts);
  split_region(t, std::vector<uint32_t>(tris.begin() + long(mid), tris.end()), max_extent, parts);
}

// A directed edge of a cluster's boundary: welded vertex ids and positions.
struct Directed {
  uint32_t a, b;
  Vec3 pa, pb;
};

// The edges of the cluster's triangles used by one of them only (no reverse edge in the cluster),
// in the triangles' order.
std::vector<Directed> boundary_edges(const Triangles& t,
                                     const std::vector<std::array<uint32_t, 3>>& v,
                                     const std::vector<uint32_t>& tris) {
  std::vector<std::pair<uint32_t, uint32_t>> sorted;
  for (uint32_t i : tris)
    for (int k = 0; k < 3; ++k) sorted.emplace_back(v[i][size_t(k)], v[i][size_t(k + 1) % 3]);
  std::sort(sorted.begin(), sorted.end());
  std::vector<Directed> bnd;
  for (uint32_t i : tris) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[i][size_t(k)], b = v[i][size_t(k + 1) % 3];
      if (std::binary_search(sorted.begin(), sorted.end(), std::make_pair(b, a))) continue;
      bnd.push_back({a, b, t.corners[i][size_t(k)], t.corners[i][size_t(k + 1) % 3]});
    }
  }
  return bnd;
}

// The boundary edges with collinear runs merged.
void outline(const std::vector<Directed>& bnd, std::vector<Vec3>& ea, std::vector<Vec3>& eb) {
  // Merge: a vertex with exactly one boundary edge in and one out, on a straight line, is
  // dropped. Chains are followed from edges whose start cannot be dropped.
  std::vector<std::pair<uint32_t, uint32_t>> out_of;  // (start vertex, edge)
  for (uint32_t e = 0; e < bnd.size(); ++e) out_of.emplace_back(bnd[e].a, e);
  std::sort(out_of.begin(), out_of.end());
  auto unique_out = [&](uint32_t vertex) -> int64_t {
    auto it = std::lower_bound(out_of.begin(), out_of.end(), std::make_pair(vertex, 0u));
    if (it == out_of.end() || it->first != vertex) return -1;
    if (it + 1 != out_of.end() && (it + 1)->first == vertex) return -1;
    return it->second;
  };
  std::vector<uint32_t> ins;
  for (const Directed& d : bnd) ins.push_back(d.b);
  std::sort(ins.begin(), ins.end());
  auto in_count = [&](uint32_t vertex) {
    return std::upper_bound(ins.begin(), ins.end(), vertex) -
           std::lower_bound(ins.begin(), ins.end(), vertex);
  };
  auto straight = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = b - a, w = c - b;
    return glm::dot(u, w) > 0.0f &&
           glm::length(glm::cross(u, w)) <= 1e-5f * glm::length(u) * glm::length(w);
  };
  // The edge arriving at each vertex whose in-count is 1.
  std::vector<std::pair<uint32_t, uint32_t>> arriving;
  for (uint32_t e = 0; e < bnd.size(); ++e) arriving.emplace_back(bnd[e].b, e);
  std::sort(arriving.begin(), arriving.end());
  auto droppable = [&](uint32_t e) {  // may edge e be absorbed into the edge arriving at its start
    const uint32_t a = bnd[e].a;
    if (in_count(a) != 1 || unique_out(a) < 0) return false;
    const uint32_t prev =
        std::lower_bound(arriving.begin(), arriving.end(), std::make_pair(a, 0u))->second;
    return prev != e && straight(bnd[prev].pa, bnd[prev].pb, bnd[e].pb);
  };
  std::vector<uint8_t> used(bnd.size(), 0);
  auto follow = [&](uint32_t e) {
    used[e] = 1;
    const Vec3 start = bnd[e].pa;
    Vec3 end = bnd[e].pb;
    for (;;) {
      const int64_t next = unique_out(bnd[e].b);
      if (next < 0 || used[size_t(next)] || !droppable(uint32_t(next))) break;
      if (!straight(start, end, bnd[size_t(next)].pb)) break;
      e = uint32_t(next);
      used[e] = 1;
      end = bnd[e].pb;
    }
    ea.push_back(start), eb.push_back(end);
  };
  for (uint32_t e = 0; e < bnd.size(); ++e)
    if (!used[e] && !droppable(e)) follow(e);
  for (uint32_t e = 0; e < bnd.size(); ++e)  // closed runs of droppable edges, if any
    if (!used[e]) follow(e);
}

// The corners of a cluster's triangles that lie on no boundary edge, once each.
void interior_vertices(const Triangles& t, const std::vector<std::array<uint32_t, 3>>& v,
                       const std::vector<uint32_t>& tris, const std::vector<Directed>& bnd,
                       std::vector<Vec3>& out) {
  std::vector<uint32_t> on_boundary;
  for (const Directed& d : bnd) on_boundary.push_back(d.a), on_boundary.push_back(d.b);
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

Clusters make_clusters(const Hierarchy& h, float max_extent) {
  const Triangles& t = h.triangles;
  const std::vector<std::array<uint32_t, 3>> v = weld(t);
  const std::vector<std::array<int32_t, 3>> nb = neighbours(v);

  // One pass of region growing with the face clusters' cone; a region whose normals all agree
  // within 0.1 degree is planar. (Growing planar regions first fragments a finely tessellated
  // sphere, whose neighbouring quads lie within a degree of each other, into thousands.)
  std::vector<uint8_t> free(t.size(), 1);
  std::vector<uint32_t> flat, starts;
  grow_regions(t, nb, kCurvedCos, free, flat, starts);
  starts.push_back(uint32_t(flat.size()));
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
    split_region(t, regions[r], max_extent, parts);
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
      const std::vector<Directed> bnd = boundary_edges(t, v, tris);
      outline(bnd, k.edge_a, k.edge_b);
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
