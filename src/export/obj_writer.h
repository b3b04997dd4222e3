// Wavefront OBJ output with per-vertex colours ("v x y z r g b"), and with textures an MTL and
// the images beside it.
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

/// Writes one "v x y z r g b" line per vertex (the display colour, tone-mapped and sRGB-encoded
/// as in PLY, as 0-1 floats: the PLY byte / 255) and one "f i j k" line per face (1-based).
/// With texture coordinates and `mtl_file` (what write_obj_materials returned), also "mtllib",
/// one "vt u v" per vertex (v up the image, as OBJ has it), faces "f i/i j/j k/k" grouped under
/// "usemtl radiosity" (no texture) and "usemtl textureN".
void write_obj(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm,
               const std::string& mtl_file = {});

/// Beside `obj_path`, the files an OBJ of a textured mesh names: STEM.mtl (materials radiosity
/// and textureN, each Kd 1 1 1, textureN with map_Kd) and each image once as STEM_textureN.png
/// (N: the first texture that shows it). Each file appears whole or not at all. Returns the
/// MTL's file name, or "" without writing anything when the mesh has no texture.
/// `write_beside`, given, writes each of those files instead: it is called with the file's
/// final path and a function that writes the file to the path it is handed (a caller staging a
/// run's outputs, run/output_files.h, renames them into place with the OBJ). Empty, each file
/// is written to a temporary name and renamed into place once all are written.
using WriteBeside =
    std::function<void(const std::string& path, const std::function<void(const std::string&)>&)>;
std::string write_obj_materials(const std::string& obj_path, const OutputMesh& mesh,
                                const WriteBeside& write_beside = {});

}  // namespace rad
