#include "mesh/output_faces.h"

namespace rad {

void SeamVertices::add(const Vec3& x, VertexRef v) { at_.try_emplace(position_bits(x), v); }

const VertexRef* SeamVertices::find(const Vec3& x) const {
  auto it = at_.find(position_bits(x));
  return it == at_.end() ? nullptr : &it->second;
}

namespace {

// Seam vertices are numbered with this bit set until the centroids are counted.
constexpr uint32_t kSeamBit = 0x80000000u;

struct Interior {
  const PolygonMesh& p;
  uint32_t self;
  const SeamVertices* seams;
  std::vector<VertexRef>& seam;

  // Appends the vertices strictly inside edge a->b, in order from a to b.
  void edge(uint32_t a, uint32_t b, std::vector<uint32_t>& out) const {
    const int64_t m = p.midpoint(a, b);
    if (m < 0) {
      if (seams) across(p.positions[a], p.positions[b], out);
      return;
    }
    edge(a, uint32_t(m), out);
    out.push_back(uint32_t(m));
    edge(uint32_t(m), b, out);
  }
  // The same beyond the polygon's own midpoints: other polygons' vertices where p's midpoints
  // would be (split_element's midpoint, to the bit).
  void across(const Vec3& a, const Vec3& b, std::vector<uint32_t>& out) const {
    const Vec3 x = (a + b) * 0.5f;
    if (x == a || x == b) return;  // the edge is a rounding step long: nothing lies inside
    const VertexRef* v = seams->find(x);
    if (!v || v->polygon == self) return;
    across(a, x, out);
    out.push_back(kSeamBit | uint32_t(seam.size()));
    seam.push_back(*v);
    across(x, b, out);
  }
};

}  // namespace

PolygonFaces triangulate_leaves(const PolygonMesh& p, uint32_t self, const SeamVertices* seams) {
  PolygonFaces f;
  const Interior interior{p, self, seams && !seams->empty() ? seams : nullptr, f.seam};
  std::vector<uint32_t> inner[3], loop;
  for_each_leaf(p, [&](uint32_t e) {
    const uint32_t* v = p.elements[e].v;
    int edges_with_points = 0, which = -1;
    for (int k = 0; k < 3; ++k) {
      inner[k].clear();
      interior.edge(v[k], v[(k + 1) % 3], inner[k]);
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
  if (!f.seam.empty()) {
    const uint32_t first = uint32_t(p.vertex_count() + f.centroids.size());
    for (uint32_t& i : f.triangles)
      if (i & kSeamBit) i = first + (i & ~kSeamBit);
  }
  return f;
}

}  // namespace rad
