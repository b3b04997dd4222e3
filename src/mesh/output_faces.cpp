#include "mesh/output_faces.h"

#include <cstring>

namespace rad {

SeamVertices::Key SeamVertices::key(const Vec3& x) {
  const Vec3 q = x + Vec3(0.0f);  // -0 as +0
  Key k;
  std::memcpy(&k.x, &q.x, 4), std::memcpy(&k.y, &q.y, 4), std::memcpy(&k.z, &q.z, 4);
  return k;
}

size_t SeamVertices::KeyHash::operator()(const Key& k) const {
  uint64_t h = (uint64_t(k.x) << 32 | k.y) * 0x9e3779b97f4a7c15ull;
  h ^= (uint64_t(k.z) + 0x632be59bd9b4e019ull) + (h << 6) + (h >> 2);
  return size_t(h ^ (h >> 31));
}

void SeamVertices::add(const Vec3& x, VertexRef v) { at_.try_emplace(key(x), v); }

const VertexRef* SeamVertices::find(const Vec3& x) const {
  auto it = at_.find(key(x));
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
      if (seams) across(p.vertices[a].position, p.vertices[b].position, out);
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
