// The solved scene flattened for writers and viewers: crack-free faces with per-vertex
// radiosity, built in one layout by one builder for every mode.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mesh/output_faces.h"
#include "solver/light_groups.h"
#include "solver/solver_state.h"

namespace rad {

/// A base-colour texture as the outputs carry it: the image (shared with the scene), this use's
/// sampler, and the cut-out when the material's alpha mask is this image's alpha.
struct OutputTexture {
  TextureMap map;
  bool mask = false;         // cut out where alpha x alpha_scale < cutoff (glTF alphaMode MASK)
  float alpha_scale = 1.0f;  // the material's alpha factor
  float cutoff = 0.5f;
  bool operator==(const OutputTexture& o) const {
    return map.image == o.map.image && map.sampler.wrap_s == o.map.sampler.wrap_s &&
           map.sampler.wrap_t == o.map.sampler.wrap_t &&
           map.sampler.nearest == o.map.sampler.nearest && mask == o.mask &&
           alpha_scale == o.alpha_scale && cutoff == o.cutoff;
  }
};

/// Faces and vertex positions. Each polygon's vertices come first, then its centroids, then the
/// neighbours' vertices on its edges (see triangulate_leaves); vertices are shared within a
/// polygon, not across polygons.
struct MeshGeometry {
  std::vector<Vec3> position;
  std::vector<uint32_t> indices;      // 3 per face
  std::vector<int32_t> face_polygon;  // the polygon each face belongs to
  /// Per vertex, its texture coordinates: its position in its polygon's original triangle
  /// mapped through that triangle's coordinates (glTF convention, v down the image); (0, 0) on
  /// a polygon without coordinates. Empty when no triangle of the scene has any, so an
  /// untextured scene costs nothing.
  std::vector<Vec2> uv;
  /// The base-colour textures of the polygons that have one and coordinates, each once; empty
  /// when there are none.
  std::vector<OutputTexture> textures;
  /// Per face, its index in `textures`, or -1 (no texture); empty when `textures` is.
  std::vector<int32_t> face_texture;
};

/// One solved view: geometry (shared between views while subdivision adds nothing) and the
/// per-vertex values over it.
struct OutputMesh {
  std::shared_ptr<const MeshGeometry> geometry = std::make_shared<const MeshGeometry>();
  std::vector<Vec3> radiosity;  // linear radiosity B = E + rho H (the solver's value)
  std::vector<Vec3> display;    // radiosity shown: B, plus rho x ambient when asked
  /// The light arriving, H of B = E + rho H (irradiance; illuminance in lux when the scene is
  /// lit by photometric lights in metres), before any surface's reflectance.
  std::vector<Vec3> irradiance;
  /// With textures (geometry->textures not empty), per vertex: its base texture's linear colour
  /// as the solver filtered it there (its reflectance over the material's factor, cut-outs'
  /// opacity included), 1 on a polygon without texture; empty otherwise. display / texel is the
  /// light a viewer multiplies the texture by (for a surface that does not emit: the material's
  /// factor times H plus the ambient term).
  std::vector<Vec3> texel;
  /// With light groups (solver/light_groups.h), their names and per group, per vertex, the
  /// radiosity B of the group's light alone (laid out as `radiosity`); empty otherwise.
  std::vector<std::string> group_names;
  std::vector<std::vector<Vec3>> group_radiosity;

  const std::vector<Vec3>& position() const { return geometry->position; }
  const std::vector<uint32_t>& indices() const { return geometry->indices; }
  const std::vector<int32_t>& face_polygon() const { return geometry->face_polygon; }
  const std::vector<Vec2>& uv() const { return geometry->uv; }
  const std::vector<OutputTexture>& textures() const { return geometry->textures; }
  const std::vector<int32_t>& face_texture() const { return geometry->face_texture; }
  size_t face_count() const { return geometry->indices.size() / 3; }
};

/// Keeps the flattened mesh of a solve up to date, incrementally: only polygons whose elements
/// changed since the last update are triangulated again. Not thread-safe.
class OutputMeshBuilder {
 public:
  /// Brings the faces up to date with `s`. Returns the geometry and sets `*changed` when it
  /// differs from the previous call's (the previous pointer is returned otherwise).
  std::shared_ptr<const MeshGeometry> update(const SolverState& s, bool* changed);

  /// Per vertex of the last update's geometry, into out's radiosity, display and irradiance:
  /// radiosity B (centroids: the mean of their three), the displayed value B + rho x `ambient`
  /// (rho: the polygon's reflectance) and the irradiance H; with textures, out.texel too.
  /// Leaves out.geometry as it is.
  void values(const SolverState& s, Vec3 ambient, OutputMesh& out) const;

  /// Per vertex of the last update's geometry, value(p, v) of the polygon vertex it stands for
  /// (centroids: the mean of their three), as `values` lays out radiosity.
  std::vector<Vec3> per_vertex(const std::function<Vec3(size_t, uint32_t)>& value) const;

  /// Forgets every polygon (after the state was replaced).
  void reset();

 private:
  struct Polygon {
    size_t vertices = SIZE_MAX, elements = SIZE_MAX;  // what the faces were made from
    PolygonFaces faces;
  };
  /// Per vertex of the last update's geometry, into `texel`: OutputMesh::texel.
  void texels(const Solution& sol, std::vector<Vec3>& texel) const;

  std::vector<Polygon> polygons_;
  std::vector<int32_t> polygon_texture_;  // per polygon its index in textures, or -1
  std::shared_ptr<const MeshGeometry> geometry_;
};

/// The whole solve flattened at once. With `ambient`, display adds Cohen's ambient term times
/// each polygon's reflectance. With light groups, each group's radiosity too.
OutputMesh make_output_mesh(const SolverState& s, bool ambient);

}  // namespace rad
