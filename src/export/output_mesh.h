// The solved scene flattened for writers and viewers: crack-free faces with per-vertex
// radiosity, built in one layout by one builder for every mode.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/output_faces.h"
#include "solver/solver_state.h"

namespace rad {

/// Faces and vertex positions. Each polygon's vertices come first, then its centroids, then the
/// neighbours' vertices on its edges (see triangulate_leaves); vertices are shared within a
/// polygon, not across polygons.
struct MeshGeometry {
  std::vector<Vec3> position;
  std::vector<uint32_t> indices;      // 3 per face
  std::vector<int32_t> face_polygon;  // the polygon each face belongs to
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

  const std::vector<Vec3>& position() const { return geometry->position; }
  const std::vector<uint32_t>& indices() const { return geometry->indices; }
  const std::vector<int32_t>& face_polygon() const { return geometry->face_polygon; }
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
  /// (rho: the polygon's reflectance) and the irradiance H. Leaves out.geometry as it is.
  void values(const SolverState& s, Vec3 ambient, OutputMesh& out) const;

  /// Forgets every polygon (after the state was replaced).
  void reset();

 private:
  struct Polygon {
    size_t vertices = SIZE_MAX, elements = SIZE_MAX;  // what the faces were made from
    PolygonFaces faces;
  };
  std::vector<Polygon> polygons_;
  std::shared_ptr<const MeshGeometry> geometry_;
};

/// The whole solve flattened at once. With `ambient`, display adds Cohen's ambient term times
/// each polygon's reflectance.
OutputMesh make_output_mesh(const SolverState& s, bool ambient);

}  // namespace rad
