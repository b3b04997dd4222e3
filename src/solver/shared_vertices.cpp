#include "solver/shared_vertices.h"

#include <algorithm>
#include <tuple>

namespace rad {

size_t SharedVertices::PlaceHash::operator()(const Place& k) const {
  return hash_position_bits(k.position, k.cluster);
}

bool SharedVertices::is_copy(uint32_t p, uint32_t v) const {
  const std::vector<VertexCopy>& cs = copies[p];
  auto it = std::lower_bound(cs.begin(), cs.end(), v,
                             [](const VertexCopy& c, uint32_t x) { return c.vertex < x; });
  return it != cs.end() && it->vertex == v;
}

bool shares_vertices(const Clusters& clusters, size_t p) {
  const uint32_t c = clusters.cluster_of[p];
  return clusters.planar[c] && clusters.polygon_count(c) > 1;
}

std::optional<SharedVertices::Place> shared_place(const Clusters& clusters, size_t p,
                                                  const Vec3& x) {
  if (!shares_vertices(clusters, p)) return std::nullopt;
  return SharedVertices::Place{clusters.cluster_of[p], position_bits(x)};
}

bool on_triangle_edge(const std::array<Vec3, 3>& c, const Vec3& x) {
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = c[size_t(k + 1) % 3] - c[size_t(k)];
    if (glm::length(glm::cross(e, x - c[size_t(k)])) <= 1e-5f * glm::dot(e, e)) return true;
  }
  return false;
}

void find_edge_midpoints(SharedVertices& sh, const Mesh& mesh, const Triangles& tris,
                         const Clusters& clusters, std::span<const uint32_t> initial_vertices) {
  sh.edge_midpoints.clear();
  for (uint32_t p = 0; p < mesh.polygons.size(); ++p) {
    const PolygonMesh& m = mesh.polygons[p];
    for (uint32_t v = initial_vertices[p]; v < m.vertex_count(); ++v) {
      const Vec3& x = m.positions[v];
      const auto place = shared_place(clusters, p, x);
      if (!place || !on_triangle_edge(tris.corners[p], x) || sh.is_copy(p, v)) continue;
      sh.edge_midpoints.try_emplace(*place, SharedVertices::Gatherer{p, v});  // lowest first
    }
  }
}

SharedVertices find_shared_vertices(const Mesh& mesh, const Clusters& clusters) {
  SharedVertices sh;
  const size_t np = mesh.polygons.size();
  sh.copies.resize(np);
  struct Key {
    SharedVertices::Place place;
    uint32_t polygon, vertex;
  };
  std::vector<Key> keys;
  for (size_t p = 0; p < np; ++p) {
    for (uint32_t v = 0; v < mesh.polygons[p].vertex_count(); ++v) {
      if (const auto k = shared_place(clusters, p, mesh.polygons[p].positions[v]))
        keys.push_back({*k, uint32_t(p), v});
    }
  }
  auto tie = [](const Key& k) { return std::tie(k.place, k.polygon, k.vertex); };
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) { return tie(a) < tie(b); });
  for (size_t i = 1, first = 0; i < keys.size(); ++i) {
    if (!(keys[i].place == keys[first].place)) {
      first = i;
      continue;
    }
    sh.copies[keys[i].polygon].push_back({keys[i].vertex, keys[first].polygon, keys[first].vertex});
  }
  for (std::vector<VertexCopy>& c : sh.copies)
    std::sort(c.begin(), c.end(),
              [](const VertexCopy& a, const VertexCopy& b) { return a.vertex < b.vertex; });
  return sh;
}

}  // namespace rad
