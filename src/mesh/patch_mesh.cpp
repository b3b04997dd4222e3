#include "mesh/patch_mesh.h"

namespace rad {

uint32_t PolygonMesh::add_vertex(const Vec3& p) {
  position.push_back(p);
  irradiance.emplace_back(0.0f);
  unshot.emplace_back(0.0f);
  shot.emplace_back(0.0f);
  major.emplace_back(0.0f);
  return uint32_t(position.size() - 1);
}

int64_t PolygonMesh::midpoint(uint32_t a, uint32_t b) const {
  auto it = midpoints.find(edge_key(a, b));
  return it == midpoints.end() ? -1 : int64_t(it->second);
}

Mesh make_mesh(const Hierarchy& h) {
  Mesh m;
  m.polygons.resize(h.triangles.size());
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    PolygonMesh& p = m.polygons[t];
    // Exactly three: most polygons of a large scene never split, and growth would round the
    // five per-vertex arrays up to four (measured: 20 bytes per vertex on a 1M-triangle scene).
    for (auto* a : {&p.position, &p.irradiance, &p.unshot, &p.shot, &p.major}) a->reserve(3);
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
