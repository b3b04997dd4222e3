#include "export/output_mesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "solver/texture_factors.h"

namespace rad {

namespace {

/// Texture coordinates at `x` on triangle p: its barycentric coordinates there (by sub-triangle
/// areas, in double, as the solver's texture factors take them) applied to the corners' own.
Vec2 uv_at(const Triangles& t, size_t p, const Vec3& x) {
  const std::array<Vec2, 3>& uv = t.uv[p];
  if (!std::isfinite(uv[0].x)) return Vec2(0.0f);
  const std::array<Vec3, 3>& c = t.corners[p];
  const DVec3 a(c[0]), b(c[1]), d(c[2]), y(x);
  const DVec3 n = glm::cross(b - a, d - a);
  const double n2 = glm::dot(n, n);
  const double wb = glm::dot(glm::cross(y - a, d - a), n) / n2;
  const double wc = glm::dot(glm::cross(b - a, y - a), n) / n2;
  const double wa = 1.0 - wb - wc;
  return Vec2(float(wa * uv[0].x + wb * uv[1].x + wc * uv[2].x),
              float(wa * uv[0].y + wb * uv[1].y + wc * uv[2].y));
}

/// Polygon p's base-colour texture as the outputs carry it, or none: without a texture or
/// without coordinates it shows its material's colour.
bool output_texture(const Triangles& t, size_t p, const SceneObject& o, OutputTexture& out) {
  if (!o.base_texture || t.uv.empty() || !is_textured(t, p, o)) return false;
  out = OutputTexture{o.base_texture};
  // A mask read from the base texture's own alpha (glTF MASK) travels with it; an OBJ map_d
  // image is another file, which the outputs do not carry.
  if (o.cutout && o.cutout.texture.image == o.base_texture.image && !o.cutout.from_red) {
    out.mask = true;
    out.alpha_scale = o.cutout.scale;
    out.cutoff = o.cutout.cutoff;
  }
  return true;
}

}  // namespace

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
  polygon_texture_.clear();
  if (!tris.uv.empty()) {
    polygon_texture_.assign(polys.size(), -1);
    for (size_t p = 0; p < polys.size(); ++p) {
      OutputTexture t;
      if (!output_texture(tris, p, s.solution.object_of(p), t)) continue;
      auto at = std::find(g->textures.begin(), g->textures.end(), t);
      if (at == g->textures.end()) at = g->textures.insert(at, t);
      polygon_texture_[p] = int32_t(at - g->textures.begin());
    }
    if (g->textures.empty()) polygon_texture_.clear();
  }
  size_t nv = 0, ni = 0;
  for (const Polygon& c : polygons_) {
    nv += c.vertices + c.faces.centroids.size() + c.faces.seam.size();
    ni += c.faces.triangles.size();
  }
  g->position.reserve(nv);
  g->indices.reserve(ni);
  g->face_polygon.reserve(ni / 3);
  if (!tris.uv.empty()) g->uv.reserve(nv);
  if (!g->textures.empty()) g->face_texture.reserve(ni / 3);
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
    if (!tris.uv.empty()) {
      // Every vertex, seams included, maps through this polygon's own triangle: its faces show
      // this polygon's texture.
      for (size_t v = base; v < g->position.size(); ++v)
        g->uv.push_back(uv_at(tris, p, g->position[v]));
    }
    if (!g->textures.empty()) {
      g->face_texture.insert(g->face_texture.end(), f.triangles.size() / 3, polygon_texture_[p]);
    }
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
  texels(sol, out.texel);
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

void OutputMeshBuilder::texels(const Solution& sol, std::vector<Vec3>& texel) const {
  texel.clear();
  if (!geometry_ || geometry_->textures.empty()) return;
  const std::vector<OutputTexture>& textures = geometry_->textures;
  texel.reserve(geometry_->position.size());
  // The texture's colour at vertex v of polygon p (textured by `t`): its reflectance over the
  // material's, which is the factor times the texture's mean. Where the material reflects
  // nothing in a channel its vertices' factors are lost, and the mean stands in.
  auto at = [&](size_t p, uint32_t v, const TextureImage& image) {
    const Vec3 rho = sol.material_of(p).reflectance, rv = sol.reflectance(p, v);
    Vec3 t = image.mean;
    for (int k = 0; k < 3; ++k) {
      if (rho[k] > 0.0f) t[k] = image.mean[k] * rv[k] / rho[k];
    }
    return t;
  };
  for (size_t p = 0; p < polygons_.size(); ++p) {
    const uint32_t n = uint32_t(polygons_[p].vertices);
    const PolygonFaces& f = polygons_[p].faces;
    const int32_t k = polygon_texture_[p];
    if (k < 0) {
      texel.insert(texel.end(), n + f.centroids.size() + f.seam.size(), Vec3(1.0f));
      continue;
    }
    const TextureImage& image = *textures[size_t(k)].map.image;
    const size_t first = texel.size();
    for (uint32_t v = 0; v < n; ++v) texel.push_back(at(p, v, image));
    for (const auto& c : f.centroids) {
      texel.push_back((texel[first + c[0]] + texel[first + c[1]] + texel[first + c[2]]) / 3.0f);
    }
    for (const VertexRef& r : f.seam) {
      // A neighbour's vertex on this polygon's edge shows the neighbour's radiosity; where the
      // neighbour has the same image (a texture running on across the edge) its texel is the
      // one in that radiosity, else the mean.
      const int32_t kr = polygon_texture_[r.polygon];
      texel.push_back(kr >= 0 && textures[size_t(kr)].map.image == textures[size_t(k)].map.image
                          ? at(r.polygon, r.vertex, image)
                          : image.mean);
    }
  }
}

void OutputMeshBuilder::reset() {
  polygons_.clear();
  polygon_texture_.clear();
  geometry_.reset();
}

std::vector<Vec3> OutputMeshBuilder::per_vertex(
    const std::function<Vec3(size_t, uint32_t)>& value) const {
  std::vector<Vec3> out;
  out.reserve(geometry_ ? geometry_->position.size() : 0);
  for (size_t p = 0; p < polygons_.size(); ++p) {
    const uint32_t n = uint32_t(polygons_[p].vertices);
    for (uint32_t v = 0; v < n; ++v) out.push_back(value(p, v));
    for (const auto& k : polygons_[p].faces.centroids)
      out.push_back((value(p, k[0]) + value(p, k[1]) + value(p, k[2])) / 3.0f);
    for (const VertexRef& r : polygons_[p].faces.seam) out.push_back(value(r.polygon, r.vertex));
  }
  return out;
}

OutputMesh make_output_mesh(const SolverState& s, bool ambient) {
  OutputMeshBuilder builder;
  OutputMesh out;
  bool changed = false;
  out.geometry = builder.update(s, &changed);
  builder.values(s, ambient ? ambient_radiosity(s.energy, s.solution) : Vec3(0.0f), out);
  if (s.solution.group_count > 0) {
    out.group_names = light_groups_kept(*s.solution.hierarchy);
    for (size_t g = 0; g < s.solution.group_count; ++g) {
      out.group_radiosity.push_back(builder.per_vertex(
          [&](size_t p, uint32_t v) { return s.solution.group_radiosity(g, p, v); }));
    }
  }
  return out;
}

}  // namespace rad
