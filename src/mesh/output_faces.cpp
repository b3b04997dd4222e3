#include "mesh/output_faces.h"

namespace rad {

namespace {

// Appends the vertices strictly inside edge a->b, in order from a to b.
void edge_interior(const PolygonMesh& p, uint32_t a, uint32_t b, std::vector<uint32_t>& out) {
  int64_t m = p.midpoint(a, b);
  if (m < 0) return;
  edge_interior(p, a, uint32_t(m), out);
  out.push_back(uint32_t(m));
  edge_interior(p, uint32_t(m), b, out);
}

}  // namespace

PolygonFaces triangulate_leaves(const PolygonMesh& p) {
  PolygonFaces f;
  std::vector<uint32_t> inner[3], loop;
  for_each_leaf(p, [&](uint32_t e) {
    const uint32_t* v = p.elements[e].v;
    int edges_with_points = 0, which = -1;
    for (int k = 0; k < 3; ++k) {
      inner[k].clear();
      edge_interior(p, v[k], v[(k + 1) % 3], inner[k]);
      if (!inner[k].empty()) ++edges_with_points, which = k;
    }
    if (edges_with_points == 0) {
      f.triangles.insert(f.triangles.end(), {v[0], v[1], v[2]});
      return;
    }
    if (edges_with_points == 1) {
      // Fan from the corner opposite the edge v[which] -> v[which+1].
      const uint32_t apex = v[(which + 2) % 3];
      uint32_t prev = v[which];
      for (uint32_t q : inner[which]) {
        f.triangles.insert(f.triangles.end(), {apex, prev, q});
        prev = q;
      }
      f.triangles.insert(f.triangles.end(), {apex, prev, v[(which + 1) % 3]});
      return;
    }
    loop.clear();
    for (int k = 0; k < 3; ++k) {
      loop.push_back(v[k]);
      loop.insert(loop.end(), inner[k].begin(), inner[k].end());
    }
    const uint32_t c = uint32_t(p.vertex_count() + f.centroids.size());
    f.centroids.push_back({v[0], v[1], v[2]});
    for (size_t i = 0; i < loop.size(); ++i) {
      f.triangles.insert(f.triangles.end(), {c, loop[i], loop[(i + 1) % loop.size()]});
    }
  });
  return f;
}

}  // namespace rad
