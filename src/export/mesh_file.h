// Writing the solved mesh to a file whose format follows its extension.
#pragma once

#include <string>

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

struct MeshFileOptions {
  ToneMap tone;
  bool ascii = false;
};

/// Throws rad::Error if rad cannot write files with this path's extension (checked before
/// solving, so a bad name costs nothing).
void check_mesh_extension(const std::string& path);

/// Writes the mesh atomically: the file appears complete or not at all.
void write_mesh_file(const std::string& path, const OutputMesh& mesh, const MeshFileOptions& o);

}  // namespace rad
