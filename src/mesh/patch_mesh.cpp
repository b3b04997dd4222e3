#include "mesh/patch_mesh.h"

namespace rad {

uint32_t PolygonMesh::add_vertex(const Vec3& p) {
  positions.push_back(p);
  return uint32_t(positions.size() - 1);
}

int64_t PolygonMesh::midpoint(uint32_t a, uint32_t b) const {
  return midpoints.find(edge_key(a, b));
}

Mesh make_mesh(const Hierarchy& h) {
  Mesh m;
  m.polygons.resize(h.triangles.size());
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    PolygonMesh& p = m.polygons[t];
    // Exactly three and one element: most polygons of a large scene never split, and growth
    // would round the arrays up to twice what they hold.
    p.positions.reserve(3);
    p.elements.reserve(1);
    for (const Vec3& c : h.triangles.corners[t]) p.add_vertex(c);
    p.elements.push_back({{0, 1, 2}, -1, h.triangles.area[t]});
  }
  return m;
}

size_t count_vertices(const Mesh& m) {
  size_t n = 0;
  for (const auto& p : m.polygons) n += p.vertex_count();
  return n;
}

size_t count_leaves(const Mesh& m) {
  size_t n = 0;
  for (const auto& p : m.polygons) for_each_leaf(p, [&](uint32_t) { ++n; });
  return n;
}

}  // namespace rad
