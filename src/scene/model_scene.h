// A model file as a scene: its groups and materials become the hierarchy of design §3.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/description.h"
#include "scene/model.h"
#include "scene/stage.h"

namespace rad {

/// --emit PATTERN=VALUE: materials whose name matches the shell pattern emit VALUE times their
/// colour scaled to a largest channel of 1 (white when black). Most model files have no
/// emitting material.
struct EmitRule {
  std::string pattern;
  float value = 0.0f;
};

/// "Lamp*=12" -> {"Lamp*", 12}. Throws rad::Error for anything else.
EmitRule parse_emit_rule(const std::string& text);

/// --light-group PATTERN=NAME: materials and lights whose name matches the shell pattern are in
/// light group NAME (ObjectFlags::group, Light::group); the last matching rule wins.
struct GroupRule {
  std::string pattern;
  std::string group;
};

/// "Lamp*=kitchen" -> {"Lamp*", "kitchen"}. Throws rad::Error for anything else.
GroupRule parse_group_rule(const std::string& text);

struct ModelOptions {
  std::vector<EmitRule> emit;
  std::vector<GroupRule> light_groups;
  /// --two-sided PATTERN: the materials, and the groups (OBJ o/g, glTF nodes), whose name
  /// matches the shell pattern are two-sided (as glTF's doubleSided); a pattern matching
  /// nothing is an error.
  std::vector<std::string> two_sided;
  /// A solve needs light; rad convert does not, and takes a model with no emitter as it is.
  bool require_emission = true;
  /// With !require_emission: say in a warning that nothing emits and how to light it (rad
  /// --check: the model is fine, the solve would refuse it).
  bool warn_unlit = false;
  /// --stage (and --sun): the model set on a floor under a light (stage.h), added by
  /// read_scene_file after the model's own scene; the model then needs no light of its own.
  std::optional<StageOptions> stage;
};

/// The scene of a model: an Assembly named after the file, one Composite per group, one Pure per
/// (group, material) with the material's reflectance (clamped to 1 per channel, with one warning
/// per material) and emission (the rules override the file's), a Light object per light of the
/// model (ObjectDescription::light; a light with intensity counts as emitting), with the model's
/// summary (SceneDescription::model). Throws rad::Error naming the --emit option when nothing emits
/// (unless !require_emission; then a warning if warn_unlit), or when a rule matches no material.
SceneDescription model_to_scene(Model m, const ModelOptions& o);

}  // namespace rad
