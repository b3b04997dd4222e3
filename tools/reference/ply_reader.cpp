#include "reference/ply_reader.h"

#include <fmt/format.h>

#include "core/error.h"
#include "scene/ply_reader.h"
#include "scene/text_file.h"

namespace rad {

PlyMesh read_radiosity_ply(const std::string& path) {
  const PlyData d = parse_ply_data(read_text_file(path, SourceLoc{path}), path);
  PlyMesh mesh;
  const char* names[6] = {"x", "y", "z", "radiosity_r", "radiosity_g", "radiosity_b"};
  const std::vector<float>* c[6];
  for (int k = 0; k < 6; ++k) c[k] = &d.column(names[k], path);
  for (size_t v = 0; v < d.vertex_count; ++v) {
    mesh.position.emplace_back((*c[0])[v], (*c[1])[v], (*c[2])[v]);
    mesh.radiosity.emplace_back((*c[3])[v], (*c[4])[v], (*c[5])[v]);
  }
  if (d.vertex.count("irradiance_r") && d.vertex.count("irradiance_g") &&
      d.vertex.count("irradiance_b")) {
    const std::vector<float>&r = d.vertex.at("irradiance_r"), &g = d.vertex.at("irradiance_g"),
          &b = d.vertex.at("irradiance_b");
    for (size_t v = 0; v < d.vertex_count; ++v) mesh.irradiance.emplace_back(r[v], g[v], b[v]);
  }
  for (size_t f = 0; f + 1 < d.face_first.size(); ++f) {
    const uint32_t n = d.face_first[f + 1] - d.face_first[f];
    if (n != 3)
      throw Error(SourceLoc{path},
                  fmt::format("face {} has {} vertices; rad writes triangles", f, n));
  }
  mesh.indices = d.face_indices;
  return mesh;
}

}  // namespace rad
