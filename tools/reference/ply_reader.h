// Reading rad's PLY output back (positions, linear radiosity, triangles) for comparisons.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace rad {

struct PlyMesh {
  std::vector<Vec3> position;
  std::vector<Vec3> radiosity;    // radiosity_r/g/b
  std::vector<Vec3> irradiance;   // irradiance_r/g/b, when the file has them (else empty)
  std::vector<uint32_t> indices;  // 3 per face
};

/// Reads a PLY (scene/ply_reader.h) with vertex properties x, y, z and radiosity_r,
/// radiosity_g, radiosity_b (and irradiance_r, _g, _b when present; others skipped) and triangle
/// faces (list vertex_indices).
/// Throws rad::Error naming the file on anything else.
PlyMesh read_radiosity_ply(const std::string& path);

}  // namespace rad
