#include "export/output_mesh.h"

#include "mesh/output_faces.h"

namespace rad {

OutputMesh make_output_mesh(const SolverState& s, bool ambient) {
  OutputMesh out;
  const Vec3 amb = ambient ? ambient_radiosity(s) : Vec3(0.0f);
  for (size_t p = 0; p < s.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.mesh.polygons[p];
    const Material& mat = s.material_of(p);
    const PolygonFaces f = triangulate_leaves(m);
    const uint32_t base = uint32_t(out.position.size());
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      out.position.push_back(m.vertices[v].position);
      out.radiosity.push_back(s.radiosity(p, v));
    }
    for (const auto& c : f.centroids) {
      out.position.push_back(
          (m.vertices[c[0]].position + m.vertices[c[1]].position + m.vertices[c[2]].position) /
          3.0f);
      out.radiosity.push_back((s.radiosity(p, c[0]) + s.radiosity(p, c[1]) + s.radiosity(p, c[2])) /
                              3.0f);
    }
    for (size_t v = base; v < out.position.size(); ++v) {
      out.display.push_back(out.radiosity[v] + mat.reflectance * amb);
    }
    for (uint32_t i : f.triangles) out.indices.push_back(base + i);
    out.face_polygon.insert(out.face_polygon.end(), f.triangles.size() / 3, int32_t(p));
  }
  return out;
}

}  // namespace rad
