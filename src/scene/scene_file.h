// The scene a path names: a description file, or a model file (by extension, model.h).
#pragma once

#include <string>

#include "scene/description.h"
#include "scene/model_scene.h"

namespace rad {

/// Parses a description (parser.h), or reads a model and makes its scene (model_scene.h), set on
/// its stage (stage.h) when `model.stage` asks for one.
/// Throws rad::Error naming the file and, where known, the line.
SceneDescription read_scene_file(const std::string& path, const ModelOptions& model = {});

}  // namespace rad
