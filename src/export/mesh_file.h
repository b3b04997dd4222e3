// Writing the solved mesh to a file whose format follows its extension.
#pragma once

#include <string>

#include "export/obj_writer.h"
#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

struct MeshFileOptions {
  ToneMap tone;
  bool ascii = false;  // PLY only: text instead of binary
  /// OBJ only: the name the OBJ will be known by (the path, or the final name when `path` is a
  /// temporary one, run/output_files.h). Given, an OBJ of a textured mesh names its MTL and
  /// images after it and writes them beside it (write_obj_materials); empty, the OBJ is written
  /// alone, without texture coordinates (a download of one file).
  std::string obj_name;
  /// OBJ only: how the MTL and images beside it are written (write_obj_materials); empty, each
  /// appears on its own once all are written.
  WriteBeside write_beside;
};

/// Throws rad::Error if rad cannot write files with this path's extension (checked before
/// solving, so a bad name costs nothing).
void check_mesh_extension(const std::string& path);

/// True for .gfo, the original program's output name (its viewer's format is gone): rad writes
/// Geomview COFF there, its closest living relative.
bool is_original_output_name(const std::string& path);

/// Writes the mesh atomically (the file appears complete or not at all) in the format its
/// extension names: .ply (write_ply), .off and .gfo (write_off), .obj (write_obj), .gltf or
/// .glb (write_gltf).
void write_mesh_file(const std::string& path, const OutputMesh& mesh, const MeshFileOptions& o);

}  // namespace rad
