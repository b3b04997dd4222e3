// Stanford PLY meshes, ASCII and binary (both byte orders): model scenes, and rad's own output
// read back by the reference tools. Hand-written: Debian packages no PLY reading library (assimp
// reads PLY among forty formats; it is not worth its size here).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "scene/model.h"

namespace rad {

/// What rad reads of a PLY file: every scalar property of the element `vertex`, by name, and
/// the lists `vertex_indices` (or `vertex_index`) of the element `face`, checked against the
/// vertex count. Other elements and properties are read past.
struct PlyData {
  size_t vertex_count = 0;
  std::map<std::string, std::vector<float>> vertex;  // one value per vertex, by property name
  std::vector<uint32_t> face_first;                  // face f: indices [face_first[f], [f + 1])
  std::vector<uint32_t> face_indices;
  /// The named vertex property, or an error naming the file when the vertices lack it.
  const std::vector<float>& column(const std::string& name, const std::string& path) const;
};

/// Parses a PLY file's bytes (any numeric types). Counts in the header are checked against the
/// file's size before anything is allocated. `comment` and `obj_info` lines are skipped; other
/// free text before the first `element` is skipped with a warning naming its line. Positions
/// (x, y, z) must be finite; another property's non-finite value reads as NaN. Throws
/// rad::Error at path:line (ASCII) or path (binary) for malformed input, an unknown header
/// line among the elements included.
PlyData parse_ply_data(std::string_view bytes, const std::string& path);

/// The model of a PLY file: its faces fan-split, in one group with one material (grey 0.8),
/// both named after the file; vertex colours are ignored, with a warning.
Model parse_ply(std::string_view bytes, const std::string& path);

Model read_ply_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
