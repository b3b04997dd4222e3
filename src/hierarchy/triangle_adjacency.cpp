#include "hierarchy/triangle_adjacency.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "core/position_bits.h"

namespace rad {

namespace {

std::vector<std::array<uint32_t, 3>> weld_corners(const Triangles& t) {
  struct Key {
    int32_t object;
    PositionBits position;
    uint32_t corner;  // 3 * triangle + k
  };
  std::vector<Key> keys(t.size() * 3);
  for (size_t i = 0; i < t.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      Key& key = keys[3 * i + size_t(k)];
      key.object = t.object[i];
      key.position = position_bits(t.corners[i][size_t(k)]);
      key.corner = uint32_t(3 * i + size_t(k));
    }
  }
  auto tie = [](const Key& a) { return std::tie(a.object, a.position, a.corner); };
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) { return tie(a) < tie(b); });
  std::vector<std::array<uint32_t, 3>> out(t.size());
  uint32_t id = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 &&
        (keys[i].object != keys[i - 1].object || keys[i].position != keys[i - 1].position)) {
      ++id;
    }
    out[keys[i].corner / 3][keys[i].corner % 3] = id;
  }
  return out;
}

std::vector<std::array<int32_t, 3>> edge_neighbours(const std::vector<std::array<uint32_t, 3>>& v) {
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

}  // namespace

Regions find_regions(const Triangles& t, float cos_limit) {
  Regions r;
  r.corners = weld_corners(t);
  const std::vector<std::array<int32_t, 3>> nb = edge_neighbours(r.corners);
  std::vector<uint8_t> free(t.size(), 1);
  std::vector<uint32_t>& out = r.triangles;
  std::vector<uint32_t>& starts = r.first;
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
  starts.push_back(uint32_t(out.size()));
  return r;
}

std::vector<BoundaryEdge> boundary_edges(const Triangles& t,
                                         const std::vector<std::array<uint32_t, 3>>& v,
                                         const std::vector<uint32_t>& tris) {
  std::vector<std::pair<uint32_t, uint32_t>> sorted;
  for (uint32_t i : tris)
    for (int k = 0; k < 3; ++k) sorted.emplace_back(v[i][size_t(k)], v[i][size_t(k + 1) % 3]);
  std::sort(sorted.begin(), sorted.end());
  std::vector<BoundaryEdge> bnd;
  for (uint32_t i : tris) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[i][size_t(k)], b = v[i][size_t(k + 1) % 3];
      if (std::binary_search(sorted.begin(), sorted.end(), std::make_pair(b, a))) continue;
      bnd.push_back({a, b, t.corners[i][size_t(k)], t.corners[i][size_t(k + 1) % 3]});
    }
  }
  return bnd;
}

void outline(const std::vector<BoundaryEdge>& bnd, double tolerance, std::vector<Vec3>& ea,
             std::vector<Vec3>& eb) {
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
  for (const BoundaryEdge& d : bnd) ins.push_back(d.b);
  std::sort(ins.begin(), ins.end());
  auto in_count = [&](uint32_t vertex) {
    return std::upper_bound(ins.begin(), ins.end(), vertex) -
           std::lower_bound(ins.begin(), ins.end(), vertex);
  };
  // Straight on: turning by under 1e-5 radian, or b within `tolerance` of the line a-c (a
  // turned or moved scene leaves a straight edge's points a rounding error of their
  // coordinates off it, which for short edges is a larger angle).
  auto straight = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = b - a, w = c - b;
    if (!(glm::dot(u, w) > 0.0f)) return false;
    if (glm::length(glm::cross(u, w)) <= 1e-5f * glm::length(u) * glm::length(w)) return true;
    const DVec3 ab = DVec3(b) - DVec3(a), ac = DVec3(c) - DVec3(a);
    return glm::length(glm::cross(ab, ac)) <= tolerance * glm::length(ac);
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

}  // namespace rad
