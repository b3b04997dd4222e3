// Wavefront OBJ with MTL materials, through tinyobjloader (Debian libtinyobjloader-dev).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "scene/model.h"

namespace rad {

/// Material name -> the folder of the MTL file that defined it.
using MaterialFolders = std::map<std::string, std::string>;

/// Parses OBJ text (UTF-8, or UTF-16 with its byte order mark) with the text of its MTL
/// libraries (concatenated). Polygons are fan-split; `o` and `g` start groups; faces take the
/// material of the last `usemtl` (or the default, grey 0.8). Kd is the reflectance, Ke the
/// emission; a map_Kd texture (found by find_texture from the material's folder in
/// `material_folders`, else `texture_folder`, each file decoded once) becomes the material's
/// base texture, read through the faces' `vt` coordinates, when `texture_folder` is not empty
/// and the image can be read (stb_image); one warning per texture that cannot. Points, lines and
/// free-form curves and surfaces are dropped with one warning per kind, and so are what rad
/// does not render: transparency (d, Tr), bump and normal maps, specular reflection, vertex
/// colours (one warning each, naming the first material that has it). Throws rad::Error at
/// path:line for malformed input, non-finite coordinates and bad indices, and at path when no face
/// is left.
Model parse_obj_text(std::string obj, std::string_view mtl, const std::string& path,
                     const std::string& texture_folder = "",
                     const MaterialFolders& material_folders = {});

/// The file a material names (`map_Kd` path, `mtllib` name) as other readers find it: '\\'
/// taken as '/', a relative path from `folder` with each part matched in any case when the
/// exact name is missing, and failing that the file's name alone beside `folder` (an absolute
/// path from the exporter's machine). Nothing when no such regular file exists.
std::optional<std::string> find_texture(const std::string& folder, std::string name);

/// The text of a file's bytes as UTF-8: a UTF-8 byte order mark dropped, UTF-16 with its mark
/// (either byte order) converted; anything else unchanged.
std::string utf8_text(std::string bytes);

/// Reads an OBJ file and the MTL files its `mtllib` lines name (relative to it, found as
/// find_texture finds files; a missing one is a warning and its materials default).
Model read_obj_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
