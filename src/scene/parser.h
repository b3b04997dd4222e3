// Parser for the scene description format (design §2), with Geomview OFF geometry files.
#pragma once

#include <string>
#include <string_view>

#include "scene/description.h"

namespace rad {

/// Reads and validates a description file. `File` paths are relative to its folder.
/// Throws rad::Error naming file:line:column of the offending token.
SceneDescription parse_scene_file(const std::string& path);

/// Same, from text in memory; `path` names it in errors and anchors relative `File` paths.
SceneDescription parse_scene_text(std::string_view text, const std::string& path);

}  // namespace rad
