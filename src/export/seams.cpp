#include "export/seams.h"

#include <algorithm>
#include <map>

namespace rad {

namespace {

// Output vertices of polygon p lying on segment a-b, as (t along a->b, radiosity), sorted.
std::vector<std::pair<float, Vec3>> on_edge(const OutputMesh& m, const std::vector<uint32_t>& verts,
                                            const Vec3& a, const Vec3& b) {
  std::vector<std::pair<float, Vec3>> out;
  const Vec3 d = b - a;
  const float len2 = glm::dot(d, d);
  for (uint32_t v : verts) {
    const Vec3 q = m.position()[v] - a;
    const float t = glm::dot(q, d) / len2;
    if (t < -1e-5f || t > 1.0f + 1e-5f) continue;
    if (glm::length(q - d * t) > 1e-5f * std::sqrt(len2)) continue;
    out.push_back({t, m.radiosity[v]});
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

Vec3 interpolate(const std::vector<std::pair<float, Vec3>>& e, float t) {
  auto hi =
      std::lower_bound(e.begin(), e.end(), t, [](const auto& x, float v) { return x.first < v; });
  if (hi == e.begin()) return hi->second;
  if (hi == e.end()) return e.back().second;
  const auto lo = hi - 1;
  const float w = (t - lo->first) / std::max(hi->first - lo->first, 1e-12f);
  return lo->second * (1.0f - w) + hi->second * w;
}

}  // namespace

SeamReport measure_seams(const OutputMesh& m, const Triangles& tris) {
  SeamReport r;
  // Vertices of each polygon, from its faces.
  std::vector<std::vector<uint32_t>> verts(tris.size());
  for (size_t f = 0; f < m.face_count(); ++f) {
    for (int k = 0; k < 3; ++k)
      verts[size_t(m.face_polygon()[f])].push_back(m.indices()[3 * f + k]);
  }
  for (auto& v : verts) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  for (const Vec3& b : m.radiosity) r.mean_radiosity += mean_component(b);
  r.mean_radiosity /= double(std::max<size_t>(1, m.radiosity.size()));
  // Edges by their corner positions.
  auto key = [](const Vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, std::vector<uint32_t>> edges;
  for (size_t p = 0; p < tris.size(); ++p) {
    for (int k = 0; k < 3; ++k) {
      auto a = key(tris.corners[p][k]), b = key(tris.corners[p][(k + 1) % 3]);
      if (b < a) std::swap(a, b);
      edges[{a, b}].push_back(uint32_t(p));
    }
  }
  double sum = 0.0;
  for (const auto& [edge, polys] : edges) {
    if (polys.size() != 2) continue;
    const uint32_t p = polys[0], q = polys[1];
    if (glm::dot(tris.normal[p], tris.normal[q]) < 0.999f) continue;
    ++r.shared_edges;
    const Vec3 a(edge.first[0], edge.first[1], edge.first[2]);
    const Vec3 b(edge.second[0], edge.second[1], edge.second[2]);
    const auto ep = on_edge(m, verts[p], a, b), eq = on_edge(m, verts[q], a, b);
    if (ep.empty() || eq.empty()) continue;
    for (const auto& [mine, other] : {std::pair{&ep, &eq}, std::pair{&eq, &ep}}) {
      for (const auto& [t, value] : *mine) {
        const double jump = max_component(glm::abs(value - interpolate(*other, t)));
        ++r.vertices_checked;
        sum += jump;
        if (jump > r.largest_jump) r.largest_jump = jump, r.where = a + (b - a) * t;
      }
    }
  }
  r.mean_jump = r.vertices_checked ? sum / double(r.vertices_checked) : 0.0;
  return r;
}

}  // namespace rad
