// Stanford PLY meshes, ASCII and binary (both byte orders). Hand-written: Debian packages no
// PLY reading library (assimp reads PLY among forty formats; it is not worth its size here).
#pragma once

#include <string>
#include <string_view>

#include "scene/model.h"

namespace rad {

/// Parses a PLY file's bytes: the vertex element's x, y, z (any numeric type) and the face
/// element's vertex_indices (or vertex_index) lists, fan-split; every other element and
/// property is read past. One group and one material (grey 0.8), both named after the file.
/// Counts in the header are checked against the file's size before anything is allocated.
/// Throws rad::Error at path:line (ASCII) or path (binary) for malformed input.
Model parse_ply(std::string_view bytes, const std::string& path);

Model read_ply_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
