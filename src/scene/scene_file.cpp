#include "scene/scene_file.h"

#include "scene/model.h"
#include "scene/parser.h"
#include "scene/stage.h"

namespace rad {

SceneDescription read_scene_file(const std::string& path, const ModelOptions& model) {
  if (!is_model_file(path)) return parse_scene_file(path);
  if (!model.stage) return model_to_scene(read_model_file(path, SourceLoc{path}), model);
  // The stage lights the model: nothing of its own need emit.
  ModelOptions lit_by_stage = model;
  lit_by_stage.require_emission = false;
  lit_by_stage.warn_unlit = false;
  SceneDescription scene = model_to_scene(read_model_file(path, SourceLoc{path}), lit_by_stage);
  add_stage(scene, *model.stage);
  return scene;
}

}  // namespace rad
