#include "scene/obj_reader.h"

// tinyobjloader is compiled here, from its header, rather than linked from its shared library:
// the fuzz target and the sanitizer builds then instrument its parser too.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "scene/text_file.h"
#include "scene/texture.h"

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

// Statements that carry geometry rad drops: only faces reflect light.
struct Dropped {
  const char* word;
  const char* what;
  size_t count = 0;
  int first_line = 0;
};

// The statements rad uses; tinyobjloader parses every other one too (skin weights, lines, points,
// curves), and has undefined behaviour there: a `vw` joint id beyond int. They carry
// nothing a radiosity solve reads, so they are blanked out before parsing, in place (a copy of
// the text would be a tenth of an import), keeping every line where it was for the error messages.
// Returns what of the model's geometry that drops (points, lines, free-form curves and surfaces).
std::vector<Dropped> blank_statements_rad_ignores(std::string& obj) {
  std::vector<Dropped> dropped = {{"p", "points (p)"},
                                  {"l", "lines (l)"},
                                  {"curv", "free-form curves (curv)"},
                                  {"curv2", "free-form curves (curv2)"},
                                  {"surf", "free-form surfaces (surf)"}};
  int line = 1;
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
    if (!keep) {
      for (Dropped& d : dropped) {
        if (word != d.word) continue;
        if (d.count++ == 0) d.first_line = line;
      }
      std::fill(obj.begin() + long(at), obj.begin() + long(end), ' ');
    }
    // A "\r\n" pair ends one line.
    if (end < obj.size() && !(obj[end] == '\r' && end + 1 < obj.size() && obj[end + 1] == '\n')) {
      ++line;
    }
    at = end + 1;
  }
  return dropped;
}

// tinyobjloader names the line of a parse error in its text ("... line 28.)"): the error is
// located there when it does.
SourceLoc located(const std::string& path, const std::string& message) {
  const size_t at = message.rfind("line ");
  int line = 0;
  if (at != std::string::npos) {
    const char* b = message.data() + at + 5;
    std::from_chars(b, message.data() + message.size(), line);
  }
  return SourceLoc{path, std::max(line, 0), 0};
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The entry of `folder` named `name`, the exact name first, else one that differs only in case
// (a model made on Windows or macOS names "wal67ar.jpg" and ships "Wal67ar.JPG").
std::optional<fs::path> entry_in(const fs::path& folder, const std::string& name) {
  std::error_code ec;
  if (fs::exists(folder / name, ec)) return folder / name;
  const std::string want = lower(name);
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (lower(it->path().filename().string()) == want) return folder / it->path().filename();
  }
  return std::nullopt;
}

// A property of materials that rad drops, said once per file for all the materials that
// have it.
struct Unused {
  size_t count = 0;
  std::string first;
  void add(const std::string& material) {
    if (count++ == 0) first = material;
  }
  // "material 'A'" or "material 'A' (and 2 more)".
  std::string materials() const {
    return "material '" + first + "'" +
           (count > 1 ? " (and " + std::to_string(count - 1) + " more)" : "");
  }
};

}  // namespace

std::optional<std::string> find_texture(const std::string& folder, std::string name) {
  // Exporters on Windows write backslashes (`map_Kd .\\wal67ar.jpg`, `textures\\wood.png`).
  std::replace(name.begin(), name.end(), '\\', '/');
  const fs::path written(name);
  std::error_code ec;
  if (written.empty()) return std::nullopt;
  // Relative paths start from the folder of the file that names them, one part at a time in
  // any case.
  if (written.is_relative()) {
    fs::path at(folder);
    bool found = true;
    for (const fs::path& part : written) {
      const std::string p = part.string();
      if (p.empty() || p == ".") continue;
      if (p == "..") {
        at /= p;
        continue;
      }
      const std::optional<fs::path> next = entry_in(at, p);
      if (!next) {
        found = false;
        break;
      }
      at = *next;
    }
    if (found && fs::is_regular_file(at, ec)) return at.string();
  } else if (fs::is_regular_file(written, ec)) {
    return written.string();
  }
  // An absolute path of the exporter's machine (C:/Users/.../wood.png), or a folder that was
  // not shipped: the file beside the model, as other readers look for it.
  if (written.has_filename()) {
    const std::optional<fs::path> beside = entry_in(folder, written.filename().string());
    if (beside && fs::is_regular_file(*beside, ec)) return beside->string();
  }
  return std::nullopt;
}

std::string utf8_text(std::string bytes) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(bytes[i]); };
  if (bytes.size() >= 3 && byte(0) == 0xEF && byte(1) == 0xBB && byte(2) == 0xBF) {
    // A UTF-8 byte order mark would glue itself to the first statement's keyword.
    return bytes.substr(3);
  }
  if (bytes.size() < 2) return bytes;
  const bool big = byte(0) == 0xFE && byte(1) == 0xFF;
  if (!big && !(byte(0) == 0xFF && byte(1) == 0xFE)) return bytes;
  // UTF-16 (Notepad's "Unicode"), either byte order: to UTF-8, an unpaired surrogate as U+FFFD.
  std::string out;
  out.reserve(bytes.size() / 2);
  const auto unit = [&](size_t i) -> uint32_t {
    return big ? (uint32_t(byte(i)) << 8 | byte(i + 1)) : (uint32_t(byte(i + 1)) << 8 | byte(i));
  };
  for (size_t i = 2; i + 1 < bytes.size(); i += 2) {
    uint32_t c = unit(i);
    if (c >= 0xD800 && c < 0xDC00 && i + 3 < bytes.size() && unit(i + 2) >= 0xDC00 &&
        unit(i + 2) < 0xE000) {
      c = 0x10000 + ((c - 0xD800) << 10) + (unit(i + 2) - 0xDC00);
      i += 2;
    } else if (c >= 0xD800 && c < 0xE000) {
      c = 0xFFFD;
    }
    if (c < 0x80) {
      out += char(c);
    } else if (c < 0x800) {
      out += char(0xC0 | (c >> 6)), out += char(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += char(0xE0 | (c >> 12)), out += char(0x80 | ((c >> 6) & 0x3F));
      out += char(0x80 | (c & 0x3F));
    } else {
      out += char(0xF0 | (c >> 18)), out += char(0x80 | ((c >> 12) & 0x3F));
      out += char(0x80 | ((c >> 6) & 0x3F)), out += char(0x80 | (c & 0x3F));
    }
  }
  return out;
}

Model parse_obj_text(std::string obj, std::string_view mtl, const std::string& path,
                     const std::string& texture_folder, const MaterialFolders& material_folders) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  obj = utf8_text(std::move(obj));
  const std::vector<Dropped> dropped = blank_statements_rad_ignores(obj);
  if (!reader.ParseFromString(obj, std::string(mtl), config)) {
    const std::string why = first_line(reader.Error());
    throw Error(located(path, why), "not a readable OBJ file: " + why);
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
  // Materials by texture they could not read: one warning per texture, not per material.
  std::map<std::string, std::string> unread;
  // Each image file decoded once, however many materials name it.
  std::map<std::string, std::shared_ptr<const TextureImage>> decoded;
  Unused transparent, bumpy, specular;  // what the materials lose
  for (const tinyobj::material_t& t : reader.GetMaterials()) {
    if (t.dissolve < 1.0f) transparent.add(t.name);
    if (!t.bump_texname.empty() || !t.normal_texname.empty()) bumpy.add(t.name);
    // Ks 0 and no map_Ks (the defaults) leave nothing specular, whatever Ns says.
    if (t.specular[0] > 0.0f || t.specular[1] > 0.0f || t.specular[2] > 0.0f ||
        !t.specular_texname.empty()) {
      specular.add(t.name);
    }
    ModelMaterial mat;
    mat.name = t.name;
    mat.loc = SourceLoc{path};
    mat.reflectance = colour(t.diffuse);
    mat.emission = colour(t.emission);
    // A texture file named by the material (`role` says which, for the warning), decoded once;
    // nullptr (and a warning) when it cannot be read.
    auto texture = [&](const std::string& name,
                       const std::string& role) -> std::shared_ptr<const TextureImage> {
      if (name.empty() || texture_folder.empty()) return nullptr;
      const auto own = material_folders.find(t.name);
      const std::string& folder = own != material_folders.end() ? own->second : texture_folder;
      const std::optional<std::string> file = find_texture(folder, name);
      std::shared_ptr<const TextureImage> image;
      if (file) {
        const auto [it, made] = decoded.try_emplace(*file);
        if (made) it->second = read_texture_file(*file);
        image = it->second;
      }
      if (!image) {
        std::string& names =
            unread[(fs::path(folder) / name).string() +
                   (file ? " (not an image stb_image decodes)" : " (no such file)")];
        names += (names.empty() ? "'" : ", '") + t.name + "'" + role;
      }
      return image;
    };
    if (!t.diffuse_texname.empty() && !texture_folder.empty()) {
      if (const auto image = texture(t.diffuse_texname, "")) {
        mat.reflectance *= image->mean;
        mat.base_texture.image = image;
        if (t.diffuse_texopt.clamp) {  // map_Kd -clamp on
          mat.base_texture.sampler.wrap_s = mat.base_texture.sampler.wrap_t =
              TextureWrap::ClampToEdge;
        }
        ++m.textures.read;
      } else {
        ++m.textures.unread;
      }
    }
    // map_Ke: emission as Kd reflects, Ke times the texture.
    if (!t.emissive_texname.empty() && !texture_folder.empty() &&
        max_component(mat.emission) > 0.0f) {
      if (const auto image = texture(t.emissive_texname, " (map_Ke)")) {
        mat.emission *= image->mean;
        mat.emissive_texture.image = image;
        if (t.emissive_texopt.clamp) {
          mat.emissive_texture.sampler.wrap_s = mat.emissive_texture.sampler.wrap_t =
              TextureWrap::ClampToEdge;
        }
        ++m.textures.read;
      } else {
        ++m.textures.unread;
      }
    }
    // map_d: a cut-out where its alpha (its grey level, in an image without alpha) is below 0.5.
    if (const auto image = texture(t.alpha_texname, " (map_d: no cut-out)")) {
      mat.cutout.texture = {image, mat.base_texture.sampler};
      mat.cutout.from_red = !image->has_alpha;
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
  for (const auto& [texture, names] : unread) {
    warn(SourceLoc{path},
         "cannot read the texture " + texture + "; material " + names + " takes its colour alone");
  }
  if (transparent.count > 0) {
    warn(SourceLoc{path}, transparent.materials() +
                              " is partly transparent (d or Tr), which rad ignores: the surface "
                              "is opaque; for holes, cut it out with an alpha texture (map_d)");
  }
  if (bumpy.count > 0) {
    warn(SourceLoc{path}, bumpy.materials() +
                              " has a bump or normal map (map_Bump, bump or norm), which rad "
                              "ignores: the surface is lit flat");
  }
  if (specular.count > 0) {
    warn(SourceLoc{path}, specular.materials() +
                              " has a specular reflection (Ks, Ns, map_Ks), which rad ignores: "
                              "surfaces reflect diffusely, by Kd alone");
  }
  if (!attrib.colors.empty()) {
    warn(SourceLoc{path},
         "the vertices' colours (v x y z r g b) are ignored: faces take their material's Kd");
  }
  const uint32_t fallback = uint32_t(m.materials.size());
  bool fallback_used = false;
  const size_t nt = attrib.texcoords.size() / 2;
  size_t uvless_faces = 0, uvless_material = 0;  // textured faces without vt, the first's

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
      std::array<Vec2, 3> uv{};
      bool has_uv = true;
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
        // OBJ's v runs up the image, glTF's (rad's) down it.
        const int vt = mesh.indices[at + k].texcoord_index;
        if (vt >= 0 && size_t(vt) < nt) {
          uv[k] =
              Vec2(attrib.texcoords[2 * size_t(vt)], 1.0f - attrib.texcoords[2 * size_t(vt) + 1]);
        } else {
          has_uv = false;
        }
      }
      at += n;
      if (!ok) continue;  // triangulated: only degenerate faces (fewer than 3) remain
      const int id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      const bool known = id >= 0 && size_t(id) < m.materials.size();
      fallback_used |= !known;
      // Coordinates matter only under a texture; the group's are one per triangle or none.
      const bool textured = known && m.materials[size_t(id)].uses_coordinates();
      if (textured && !has_uv && uvless_faces++ == 0) uvless_material = size_t(id);
      if (textured) {
        g.triangle_uvs.resize(g.triangles.size(), kNoTextureCoordinates);
        g.triangle_uvs.push_back(has_uv ? uv : kNoTextureCoordinates);
      } else if (!g.triangle_uvs.empty()) {
        g.triangle_uvs.push_back(kNoTextureCoordinates);
      }
      g.triangles.push_back(tri);
      g.material.push_back(known ? uint32_t(id) : fallback);
    }
    if (!g.triangles.empty()) m.groups.push_back(std::move(g));
  }
  if (uvless_faces > 0) {
    warn(SourceLoc{path}, std::to_string(uvless_faces) + " faces of textured material '" +
                              m.materials[uvless_material].name +
                              "' (the first) have no texture coordinates (vt): they reflect "
                              "the texture's mean colour" +
                              (m.materials[uvless_material].cutout ? " and are not cut out" : ""));
  }
  if (fallback_used) m.materials.push_back(fallback_material("default", SourceLoc{path}));
  // What the model loses, once per kind at its first line; a model of nothing else is refused.
  std::string lost;
  for (const Dropped& d : dropped) {
    if (d.count == 0) continue;
    const std::string what = std::to_string(d.count) + " " + d.what + " (the first at line " +
                             std::to_string(d.first_line) + ")";
    lost += (lost.empty() ? "" : ", ") + what;
    if (!m.groups.empty()) {
      warn(SourceLoc{path, d.first_line, 1},
           std::to_string(d.count) + " " + d.what + " skipped: only faces reflect light");
    }
  }
  if (m.groups.empty()) {
    if (!lost.empty()) {
      throw Error(SourceLoc{path}, "has no faces, only " + lost +
                                       ", which reflect no light: export the model's surfaces");
    }
    throw Error(SourceLoc{path}, nv > 0 ? "has no faces (" + std::to_string(nv) +
                                              " vertices but no 'f' line): a point cloud has no "
                                              "surface to light"
                                        : "has no faces");
  }
  return m;
}

Model read_obj_file(const std::string& path, const SourceLoc& requested_at) {
  std::string obj = utf8_text(read_text_file(path, requested_at));
  const fs::path folder = fs::path(path).parent_path();
  // The MTL libraries: read here (regular files only, like every input) and handed over as text,
  // with the folder of each one's materials (their texture paths start there).
  std::string mtl;
  MaterialFolders folders;
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
      std::replace(name.begin(), name.end(), '\\', '/');
      const std::optional<std::string> found = find_texture(folder.string(), name);
      const fs::path p = found ? fs::path(*found) : folder / name;
      try {
        const std::string library =
            utf8_text(read_text_file(p.string(), SourceLoc{path, number, 1}));
        std::istringstream lines(library);
        for (std::string l; std::getline(lines, l);) {
          std::istringstream words(l);
          std::string word, material;
          if (words >> word >> material && word == "newmtl") {
            folders.emplace(material, p.parent_path().empty() ? "." : p.parent_path().string());
          }
        }
        mtl += library;
        mtl += "\n";
      } catch (const Error& e) {
        warn(SourceLoc{path, number, 1}, "material library " + name + " skipped: " + e.message());
      }
    }
  }
  return parse_obj_text(std::move(obj), mtl, path, folder.empty() ? "." : folder.string(), folders);
}

}  // namespace rad
