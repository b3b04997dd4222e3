#include "export/output_mesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace rad {

std::shared_ptr<const MeshGeometry> OutputMeshBuilder::update(const SolverState& s, bool* changed) {
  const std::vector<PolygonMesh>& polys = s.solution.mesh.polygons;
  const Clusters& clusters = s.scene.clusters;
  const Triangles& tris = s.solution.hierarchy->triangles;
  bool any = !geometry_ || polygons_.size() != polys.size();
  polygons_.resize(polys.size());
  // Elements are only ever added (split into four), so unchanged counts mean unchanged faces;
  // a polygon of a planar cluster also takes its neighbours' midpoints on shared edges, so the
  // whole cluster is triangulated again when one of its polygons changed.
  std::vector<uint32_t> clusters_changed;
  for (size_t p = 0; p < polys.size(); ++p) {
    Polygon& c = polygons_[p];
    if (c.vertices == polys[p].vertex_count() && c.elements == polys[p].elements.size()) continue;
    c.vertices = polys[p].vertex_count();
    c.elements = polys[p].elements.size();
    any = true;
    const uint32_t k = clusters.cluster_of[p];
    if (shares_vertices(clusters, p)) {
      clusters_changed.push_back(k);
    } else {
      c.faces = triangulate_leaves(polys[p], uint32_t(p));
    }
  }
  std::sort(clusters_changed.begin(), clusters_changed.end());
  clusters_changed.erase(std::unique(clusters_changed.begin(), clusters_changed.end()),
                         clusters_changed.end());
  tbb::parallel_for(size_t(0), clusters_changed.size(), [&](size_t i) {
    const uint32_t k = clusters_changed[i];
    SeamVertices seams;
    for (uint32_t j = clusters.first[k]; j < clusters.first[k + 1]; ++j) {
      const uint32_t q = clusters.polygons[j];
      const PolygonMesh& m = polys[q];
      for (uint32_t v = 0; v < m.vertex_count(); ++v) {
        if (on_triangle_edge(tris.corners[q], m.positions[v]))
          seams.add(m.positions[v], VertexRef{q, v});
      }
    }
    for (uint32_t j = clusters.first[k]; j < clusters.first[k + 1]; ++j) {
      const uint32_t q = clusters.polygons[j];
      polygons_[q].faces = triangulate_leaves(polys[q], q, &seams);
    }
  });
  *changed = any;
  if (!any) return geometry_;
  auto g = std::make_shared<MeshGeometry>();
  size_t nv = 0, ni = 0;
  for (const Polygon& c : polygons_) {
    nv += c.vertices + c.faces.centroids.size() + c.faces.seam.size();
    ni += c.faces.triangles.size();
  }
  g->position.reserve(nv);
  g->indices.reserve(ni);
  g->face_polygon.reserve(ni / 3);
  for (size_t p = 0; p < polys.size(); ++p) {
    const PolygonMesh& m = polys[p];
    const PolygonFaces& f = polygons_[p].faces;
    const uint32_t base = uint32_t(g->position.size());
    g->position.insert(g->position.end(), m.positions.begin(), m.positions.end());
    for (const auto& k : f.centroids) {
      g->position.push_back((m.positions[k[0]] + m.positions[k[1]] + m.positions[k[2]]) / 3.0f);
    }
    for (const VertexRef& r : f.seam) g->position.push_back(polys[r.polygon].positions[r.vertex]);
    for (uint32_t i : f.triangles) g->indices.push_back(base + i);
    g->face_polygon.insert(g->face_polygon.end(), f.triangles.size() / 3, int32_t(p));
  }
  geometry_ = std::move(g);
  return geometry_;
}

void OutputMeshBuilder::values(const SolverState& s, Vec3 ambient, OutputMesh& out) const {
  std::vector<Vec3>& radiosity = out.radiosity;
  std::vector<Vec3>& display = out.display;
  std::vector<Vec3>& irradiance = out.irradiance;
  radiosity.clear(), display.clear(), irradiance.clear();
  const size_t count = geometry_ ? geometry_->position.size() : 0;
  radiosity.reserve(count), display.reserve(count), irradiance.reserve(count);
  const Solution& sol = s.solution;
  auto h = [&](size_t p, uint32_t v) { return sol.vertex_states[p][v].irradiance; };
  auto shown = [&](size_t p, uint32_t v) { return sol.reflectance(p, v) * ambient; };
  for (size_t p = 0; p < polygons_.size(); ++p) {
    const uint32_t n = uint32_t(polygons_[p].vertices);
    for (uint32_t v = 0; v < n; ++v) {
      radiosity.push_back(sol.radiosity(p, v));
      irradiance.push_back(h(p, v));
      display.push_back(radiosity.back() + shown(p, v));
    }
    for (const auto& k : polygons_[p].faces.centroids) {
      radiosity.push_back(
          (sol.radiosity(p, k[0]) + sol.radiosity(p, k[1]) + sol.radiosity(p, k[2])) / 3.0f);
      irradiance.push_back((h(p, k[0]) + h(p, k[1]) + h(p, k[2])) / 3.0f);
      display.push_back(radiosity.back() +
                        (sol.texture_factors[p].empty()
                             ? shown(p, k[0])
                             : (shown(p, k[0]) + shown(p, k[1]) + shown(p, k[2])) / 3.0f));
    }
    for (const VertexRef& r : polygons_[p].faces.seam) {
      radiosity.push_back(sol.radiosity(r.polygon, r.vertex));
      irradiance.push_back(h(r.polygon, r.vertex));
      // A neighbour's vertex on this polygon's edge, shown with this polygon's material.
      display.push_back(radiosity.back() + sol.material_of(p).reflectance * ambient);
    }
  }
}

void OutputMeshBuilder::reset() {
  polygons_.clear();
  geometry_.reset();
}

OutputMesh make_output_mesh(const SolverState& s, bool ambient) {
  OutputMeshBuilder builder;
  OutputMesh out;
  bool changed = false;
  out.geometry = builder.update(s, &changed);
  builder.values(s, ambient ? ambient_radiosity(s.energy, s.solution) : Vec3(0.0f), out);
  return out;
}

}  // namespace rad
