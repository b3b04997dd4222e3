#include "scene/scene_file.h"

#include "scene/model.h"
#include "scene/parser.h"

namespace rad {

SceneDescription read_scene_file(const std::string& path, const ModelOptions& model) {
  if (is_model_file(path)) return model_to_scene(read_model_file(path, SourceLoc{path}), model);
  return parse_scene_file(path);
}

}  // namespace rad
