// An output mesh written field by field in a test, then viewed as the writers take it.
#pragma once

#include <memory>
#include <vector>

#include "export/output_mesh.h"

namespace rad::testing {

struct MeshParts {
  std::vector<Vec3> position, radiosity, display, irradiance;
  std::vector<uint32_t> indices;
  std::vector<int32_t> face_polygon;

  size_t face_count() const { return indices.size() / 3; }
  OutputMesh view() const {
    OutputMesh m;
    auto g = std::make_shared<MeshGeometry>();
    g->position = position, g->indices = indices, g->face_polygon = face_polygon;
    m.geometry = std::move(g);
    m.radiosity = radiosity;
    m.display = display;
    m.irradiance = irradiance;
    return m;
  }
};

}  // namespace rad::testing
