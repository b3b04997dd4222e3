// The solver's mesh flattened for snapshots, incrementally: only polygons whose elements
// changed since the last snapshot are triangulated again.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/output_faces.h"
#include "serve/snapshot.h"
#include "solver/solver_state.h"

namespace rad {

/// Faces and per-vertex values in make_output_mesh's layout (each polygon's vertices, then its
/// centroids; see triangulate_leaves), so snapshots export exactly as `rad` writes. Not
/// thread-safe: the session's solver thread owns it.
class FlatMesh {
 public:
  /// Brings the faces up to date with `s`. Returns the geometry and sets `*changed` when it
  /// differs from the previous call's (the previous pointer is returned otherwise).
  std::shared_ptr<const SnapshotGeometry> update(const SolverState& s, bool* changed);

  /// Per vertex of the last update's geometry: radiosity B (centroids: the mean of their three)
  /// and the displayed value B + rho x `ambient` (rho: the polygon's reflectance).
  void values(const SolverState& s, Vec3 ambient, std::vector<Vec3>& radiosity,
              std::vector<Vec3>& display) const;

  /// Forgets every polygon (after the state was replaced).
  void reset();

 private:
  struct Polygon {
    size_t vertices = SIZE_MAX, elements = SIZE_MAX;  // what the faces were made from
    PolygonFaces faces;
  };
  std::vector<Polygon> polygons_;
  std::shared_ptr<const SnapshotGeometry> geometry_;
};

}  // namespace rad
