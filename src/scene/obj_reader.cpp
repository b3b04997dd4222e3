#include "scene/obj_reader.h"

// tinyobjloader is compiled here, from its header, rather than linked from its shared library:
// the fuzz target and the sanitizer builds then instrument its parser too.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "scene/text_file.h"
#include "scene/texture_mean.h"

namespace rad {

namespace {

namespace fs = std::filesystem;

Vec3 colour(const tinyobj::real_t c[3]) { return {float(c[0]), float(c[1]), float(c[2])}; }

// tinyobjloader's messages, one per line, start with "WARN: " or "ERROR: ".
std::string first_line(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  for (const char* p : {"ERROR: ", "WARN: "}) {
    if (line.rfind(p, 0) == 0) line = line.substr(std::string(p).size());
  }
  return line;
}

// The statements rad uses; tinyobjloader parses every other one too (skin weights, lines, points,
// curves), and fuzzing found undefined behaviour there: a `vw` joint id beyond int. They carry
// nothing a radiosity solve reads, so they are blanked out before parsing, in place (a copy of
// the text was a tenth of an import), keeping every line where it was for the error messages.
void blank_statements_rad_ignores(std::string& obj) {
  for (size_t at = 0; at < obj.size();) {
    // tinyobjloader ends a line at '\r' too (a lone one included): so must the filter, or a
    // statement after a '\r' would ride through on a kept line (fuzzing found a `vw` so).
    size_t end = at;  // (find_first_of calls memchr per byte)
    while (end < obj.size() && obj[end] != '\n' && obj[end] != '\r') ++end;
    size_t k = at;
    while (k < end && (obj[k] == ' ' || obj[k] == '\t')) ++k;
    size_t w = k;
    while (w < end && !std::isspace(static_cast<unsigned char>(obj[w]))) ++w;
    const std::string_view word(obj.data() + k, w - k);
    bool keep = false;
    for (const char* kept : {"v", "f", "vt", "vn", "o", "g", "usemtl", "mtllib", "s"}) {
      keep |= word == kept;
    }
    if (!keep) std::fill(obj.begin() + long(at), obj.begin() + long(end), ' ');
    at = end + 1;
  }
}

}  // namespace

Model parse_obj_text(std::string obj, std::string_view mtl, const std::string& path,
                     const std::string& texture_folder) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  blank_statements_rad_ignores(obj);
  if (!reader.ParseFromString(obj, std::string(mtl), config)) {
    throw Error(SourceLoc{path}, "not a readable OBJ file: " + first_line(reader.Error()));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const size_t nv = attrib.vertices.size() / 3;
  for (size_t i = 0; i < attrib.vertices.size(); ++i) {
    if (!std::isfinite(attrib.vertices[i])) {
      throw Error(SourceLoc{path}, "vertex " + std::to_string(i / 3 + 1) + " is not finite");
    }
  }

  Model m;
  m.path = path;
  for (const tinyobj::material_t& t : reader.GetMaterials()) {
    ModelMaterial mat;
    mat.name = t.name;
    mat.loc = SourceLoc{path};
    mat.reflectance = colour(t.diffuse);
    mat.emission = colour(t.emission);
    if (!t.diffuse_texname.empty() && !texture_folder.empty()) {
      const fs::path tex = fs::path(texture_folder) / t.diffuse_texname;
      if (const std::optional<Vec3> mean = mean_texture_colour(tex.string())) {
        mat.reflectance *= *mean;
      } else {
        warn(SourceLoc{path}, "material '" + t.name + "': cannot read its texture " + tex.string() +
                                  "; using Kd alone");
      }
    }
    bool bad = false;
    for (int c = 0; c < 3; ++c) {
      bad |= !(mat.reflectance[c] >= 0.0f && std::isfinite(mat.reflectance[c])) ||
             !(mat.emission[c] >= 0.0f && std::isfinite(mat.emission[c]));
    }
    if (bad) {
      throw Error(SourceLoc{path},
                  "material '" + t.name + "' has a negative or non-finite Kd or Ke");
    }
    m.materials.push_back(std::move(mat));
  }
  const uint32_t fallback = uint32_t(m.materials.size());
  bool fallback_used = false;

  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    ModelGroup g;
    g.name = shape.name.empty() ? "unnamed" : shape.name;
    const tinyobj::mesh_t& mesh = shape.mesh;
    g.triangles.reserve(mesh.num_face_vertices.size());
    g.material.reserve(mesh.num_face_vertices.size());
    size_t at = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t n = mesh.num_face_vertices[f];
      if (at + n > mesh.indices.size()) throw Error(SourceLoc{path}, "truncated face list");
      std::array<Vec3, 3> tri;
      bool ok = n == 3;
      for (size_t k = 0; k < 3 && ok; ++k) {
        const int v = mesh.indices[at + k].vertex_index;
        if (v < 0 || size_t(v) >= nv) {
          throw Error(SourceLoc{path}, "a face of group '" + g.name + "' names vertex " +
                                           std::to_string(int64_t(v) + 1) + " of " +
                                           std::to_string(nv));
        }
        tri[k] =
            Vec3(float(attrib.vertices[3 * size_t(v)]), float(attrib.vertices[3 * size_t(v) + 1]),
                 float(attrib.vertices[3 * size_t(v) + 2]));
      }
      at += n;
      if (!ok) continue;  // triangulated: only degenerate faces (fewer than 3) remain
      const int id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      const bool known = id >= 0 && size_t(id) < m.materials.size();
      fallback_used |= !known;
      g.triangles.push_back(tri);
      g.material.push_back(known ? uint32_t(id) : fallback);
    }
    if (!g.triangles.empty()) m.groups.push_back(std::move(g));
  }
  if (fallback_used) m.materials.push_back({"default", Vec3(0.8f), Vec3(0.0f), SourceLoc{path}});
  if (m.groups.empty()) throw Error(SourceLoc{path}, "has no faces");
  return m;
}

Model read_obj_file(const std::string& path, const SourceLoc& requested_at) {
  std::string obj = read_text_file(path, requested_at);
  const fs::path folder = fs::path(path).parent_path();
  // The MTL libraries: read here (regular files only, like every input) and handed over as text.
  std::string mtl;
  const std::string_view text(obj);
  int number = 0;
  for (size_t at = 0; at < text.size(); at = std::min(text.find('\n', at), text.size()) + 1) {
    ++number;
    const std::string_view line = text.substr(at, text.find('\n', at) - at);
    if (line.size() < 7 || line.compare(0, 6, "mtllib") != 0 ||
        !std::isspace(static_cast<unsigned char>(line[6])))
      continue;
    std::istringstream names{std::string(line.substr(7))};
    for (std::string name; names >> name;) {
      const fs::path p = folder / name;
      try {
        mtl += read_text_file(p.string(), SourceLoc{path, number, 1});
        mtl += "\n";
      } catch (const Error& e) {
        warn(SourceLoc{path, number, 1}, "material library " + name + " skipped: " + e.message());
      }
    }
  }
  return parse_obj_text(std::move(obj), mtl, path, folder.empty() ? "." : folder.string());
}

}  // namespace rad
