// The solved scene flattened for writers: crack-free faces with per-vertex radiosity.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/solver_state.h"

namespace rad {

struct OutputMesh {
  std::vector<Vec3> position;
  std::vector<Vec3> radiosity;        // linear radiosity B = E + rho H (the solver's value)
  std::vector<Vec3> display;          // radiosity shown: B, plus rho x ambient when asked
  std::vector<uint32_t> indices;      // 3 per face
  std::vector<int32_t> face_polygon;  // the polygon each face belongs to

  size_t face_count() const { return indices.size() / 3; }
};

/// Every leaf element of every polygon as faces (T-vertices split, see triangulate_leaves).
/// Vertices are shared within a polygon, not across polygons. With `ambient`, display adds
/// Cohen's ambient term times each polygon's reflectance.
OutputMesh make_output_mesh(const SolverState& s, bool ambient);

}  // namespace rad
