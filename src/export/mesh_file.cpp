#include "export/mesh_file.h"

#include <algorithm>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_extension.h"
#include "export/gltf_writer.h"
#include "export/obj_writer.h"
#include "export/off_writer.h"
#include "export/ply_writer.h"

namespace rad {

void check_mesh_extension(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e != ".ply" && e != ".off" && e != ".gfo" && e != ".obj" && e != ".gltf" && e != ".glb") {
    throw Error(SourceLoc{path}, "unknown output format '" + e +
                                     "' (expected .ply, .off, .gfo, .obj, .gltf or .glb)");
  }
}

bool is_original_output_name(const std::string& path) { return lower_extension(path) == ".gfo"; }

void write_mesh_file(const std::string& path, const OutputMesh& mesh, const MeshFileOptions& o) {
  check_mesh_extension(path);
  const std::string e = lower_extension(path);
  AtomicFile f(path);
  if (e == ".ply") {
    write_ply(f.stream(), mesh, o.tone, o.ascii);
  } else if (e == ".off" || e == ".gfo") {
    write_off(f.stream(), mesh, o.tone);
  } else if (e == ".obj") {
    const std::string mtl =
        o.obj_name.empty() ? "" : write_obj_materials(o.obj_name, mesh, o.write_beside);
    write_obj(f.stream(), mesh, o.tone, mtl);
  } else {
    write_gltf(f.stream(), mesh, o.tone, e == ".glb");
  }
  f.commit();
}

}  // namespace rad
