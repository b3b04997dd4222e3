// Wavefront OBJ with MTL materials, through tinyobjloader (Debian libtinyobjloader-dev).
#pragma once

#include <string>
#include <string_view>

#include "scene/model.h"

namespace rad {

/// Parses OBJ text with the text of its MTL libraries (concatenated). Polygons are fan-split;
/// `o` and `g` start groups; faces take the material of the last `usemtl` (or the default, grey
/// 0.8). Kd is the reflectance, Ke the emission; a map_Kd texture multiplies Kd by its mean
/// colour when `texture_folder` is not empty and the image can be read (stb_image). Throws
/// rad::Error at path:line for malformed input, non-finite coordinates and bad indices.
Model parse_obj_text(std::string obj, std::string_view mtl, const std::string& path,
                     const std::string& texture_folder = "");

/// Reads an OBJ file and the MTL files its `mtllib` lines name (relative to it; a missing one
/// is a warning and its materials default).
Model read_obj_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
