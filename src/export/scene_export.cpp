#include "export/scene_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_extension.h"
#include "export/gltf_writer.h"
#include "export/welded_mesh.h"
#include "scene/description_writer.h"

namespace rad {

namespace {

// The object's names from its root down, joined by '/': the hierarchy as far as a flat list of
// groups holds it.
std::string path_name(const Hierarchy& h, int32_t object) {
  std::string name = h.objects[size_t(object)].name;
  for (int32_t p = h.objects[size_t(object)].parent; p >= 0; p = h.objects[size_t(p)].parent) {
    name = h.objects[size_t(p)].name + "/" + name;
  }
  return name;
}

// OBJ and MTL names end at white space: it becomes '_'; a name taken already gets a number.
std::string unique_word(const std::string& name, std::set<std::string>& taken) {
  std::string w = name.empty() ? "unnamed" : name;
  for (char& c : w) {
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  }
  std::string u = w;
  for (int k = 2; !taken.insert(u).second; ++k) u = fmt::format("{}_{}", w, k);
  return u;
}

// A name inside a comment line: no line breaks, and no "end_header" to end a PLY header early.
std::string comment_text(const std::string& name) {
  std::string c;
  for (char ch : name) c += (ch == '\n' || ch == '\r') ? ' ' : ch;
  for (size_t at; (at = c.find("end_header")) != std::string::npos;) c.replace(at, 3, "end-");
  return c;
}

std::string number(float v) { return fmt::format("{:.9g}", v); }

void write_obj_scene(const std::string& path, const Hierarchy& h) {
  const std::filesystem::path mtl_path = std::filesystem::path(path).replace_extension(".mtl");
  std::set<std::string> groups, materials;
  std::vector<std::string> material_of(h.objects.size());
  AtomicFile mtl(mtl_path.string());
  mtl.stream() << "# materials of " << comment_text(h.scene_name) << ", written by rad convert\n";
  for (size_t i = 0; i < h.objects.size(); ++i) {
    const SceneObject& o = h.objects[i];
    if (o.kind != ObjectKind::Pure) continue;
    material_of[i] = unique_word(o.name, materials);
    const Vec3 rho = o.material.reflectance, e = o.material.emission;
    mtl.stream() << "newmtl " << material_of[i] << "\nKd " << number(rho.x) << ' ' << number(rho.y)
                 << ' ' << number(rho.z) << '\n';
    if (max_component(e) > 0.0f) {
      mtl.stream() << "Ke " << number(e.x) << ' ' << number(e.y) << ' ' << number(e.z) << '\n';
    }
    mtl.stream() << "illum 1\n";
  }
  AtomicFile obj(path);
  std::ostream& out = obj.stream();
  out << "# " << comment_text(h.scene_name) << ", written by rad convert\nmtllib "
      << mtl_path.filename().string() << '\n';
  uint64_t base = 1;  // OBJ indices are 1-based and global
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (material_of[i].empty()) continue;
    const WeldedMesh w = weld_pure(h, int32_t(i));
    out << "g " << unique_word(path_name(h, int32_t(i)), groups) << "\nusemtl " << material_of[i]
        << '\n';
    for (const Vec3& p : w.position) {
      out << "v " << number(p.x) << ' ' << number(p.y) << ' ' << number(p.z) << '\n';
    }
    for (size_t t = 0; t < w.indices.size(); t += 3) {
      out << "f " << base + w.indices[t] << ' ' << base + w.indices[t + 1] << ' '
          << base + w.indices[t + 2] << '\n';
    }
    base += w.position.size();
  }
  mtl.commit();
  obj.commit();
}

void write_ply_scene(const std::string& path, const Hierarchy& h) {
  std::vector<WeldedMesh> meshes;
  std::vector<Vec3> colour;
  size_t vertices = 0, faces = 0;
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].kind != ObjectKind::Pure) continue;
    meshes.push_back(weld_pure(h, int32_t(i)));
    colour.push_back(h.objects[i].material.reflectance);
    vertices += meshes.back().position.size();
    faces += meshes.back().indices.size() / 3;
  }
  AtomicFile f(path);
  std::ostream& out = f.stream();
  out << "ply\nformat ascii 1.0\ncomment " << comment_text(h.scene_name)
      << ", written by rad convert: rgb = reflectance x 255 (linear)\nelement vertex " << vertices
      << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (size_t k = 0; k < meshes.size(); ++k) {
    const Vec3 c = glm::round(glm::clamp(colour[k], 0.0f, 1.0f) * 255.0f);
    for (const Vec3& p : meshes[k].position) {
      out << number(p.x) << ' ' << number(p.y) << ' ' << number(p.z) << ' ' << int(c.x) << ' '
          << int(c.y) << ' ' << int(c.z) << '\n';
    }
  }
  size_t base = 0;
  for (const WeldedMesh& m : meshes) {
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      out << "3 " << base + m.indices[t] << ' ' << base + m.indices[t + 1] << ' '
          << base + m.indices[t + 2] << '\n';
    }
    base += m.position.size();
  }
  f.commit();
}

}  // namespace

void check_scene_extension(const std::string& path) {
  const std::string e = lower_extension(path);
  // OBJ readers split `mtllib` at white space: a material library named with a space is lost.
  const std::string file = std::filesystem::path(path).filename().string();
  if (e == ".obj" && file.find_first_of(" \t") != std::string::npos) {
    throw Error(SourceLoc{path},
                "an OBJ's name may not hold white space: its 'mtllib' line "
                "would not name its .mtl for OBJ readers");
  }
  if (e != ".des" && e != ".obj" && e != ".gltf" && e != ".glb" && e != ".ply") {
    throw Error(SourceLoc{path},
                "rad convert cannot write '" + e + "' (expected .des, .obj, .gltf, .glb or .ply)");
  }
}

std::vector<std::string> write_scene_file(const std::string& path, const SceneDescription& scene,
                                          const Hierarchy& h) {
  check_scene_extension(path);
  const std::string e = lower_extension(path);
  std::vector<std::string> lost;
  if (e == ".des") {
    for (const ObjectDescription& o : scene.objects) {
      if (o.kind == ObjectKind::Pure && o.copy_of < 0 && !material_is_writable(o.material)) {
        lost.push_back(fmt::format(
            "'{}': its emission's colour differs from its reflectance's, and a description "
            "has one Color for both (written with the reflectance's colour)",
            o.name));
      }
    }
    AtomicFile f(path);
    write_description(scene, f.stream());
    f.commit();
    return lost;
  }
  bool placed = false, flagged = false;
  for (const ObjectDescription& o : scene.objects) {
    placed |= o.copy_of >= 0 || !o.transforms.empty();
    flagged |= o.flags.casts_shadows || o.flags.receives_shadows || o.flags.has_lights;
  }
  if (placed) lost.push_back("copies and transforms are written as placed triangles");
  if (flagged) lost.push_back("CastsShadows, ReceivesShadows and Lights flags are not kept");
  if (e == ".obj") {
    write_obj_scene(path, h);
    lost.push_back("the hierarchy is kept as group names (its path, joined by '/')");
  } else if (e == ".ply") {
    write_ply_scene(path, h);
    lost.push_back(
        "PLY holds no materials or hierarchy: reflectance is written as vertex colours, "
        "emission is lost, and rad reads the file back as one grey (0.8) Pure");
  } else {
    AtomicFile f(path);
    write_scene_gltf(f.stream(), h, e == ".glb");
    f.commit();
  }
  return lost;
}

}  // namespace rad
