#include "run/scene_checks.h"

#include "core/error.h"
#include "core/math.h"
#include "scene/model.h"

namespace rad {

void check_scene_input(const SceneInput& in) {
  if (is_model_file(in.path)) return;
  if (in.model.stage) {
    throw Error(SourceLoc{in.path},
                "--stage sets a model (.obj, .ply, .gltf, .glb) on a floor under a light; a "
                "description places its own floor and lights: leave --stage out (rad convert "
                "MODEL staged.des --stage writes a staged model as a description to start from)");
  }
  if (!in.model.light_groups.empty()) {
    throw Error(SourceLoc{in.path},
                "--light-group names the materials and lights of a model (.obj, .ply, .gltf, "
                ".glb); in a description, give the object or light a Group flag instead "
                "(Group \"kitchen\")");
  }
  if (!in.model.two_sided.empty()) {
    throw Error(SourceLoc{in.path},
                "--two-sided names the materials and groups of a model (.obj, .ply, .gltf, "
                ".glb); in a description, give the object a TwoSided Yes line instead");
  }
  if (in.model.emit.empty()) return;
  throw Error(SourceLoc{in.path},
              "--emit names the materials of a model (.obj, .ply, .gltf, .glb); in a "
              "description, give the lamp's object an Emission line instead (Emission 10)");
}

bool emits_light(const Hierarchy& h) {
  for (const Light& l : h.lights)
    if (l.intensity > 0.0f && max_component(l.colour) > 0.0f) return true;
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const Material& m = h.objects[size_t(h.triangles.object[t])].material;
    if (h.triangles.area[t] > 0.0f && max_component(m.emission) > 0.0f) return true;
  }
  return false;
}

void require_light(const Hierarchy& h, const SceneInput& in, const SolverOptions& o) {
  if (o.max_shots == 0 || emits_light(h)) return;
  const std::string how =
      is_model_file(in.path)
          ? "name the lamps' materials with --emit 'PATTERN=VALUE' (e.g. --emit 'Lamp*=10')"
          : "give a lamp's object an Emission above 0 (Emission 10)";
  throw Error(SourceLoc{in.path},
              "nothing in this scene emits light, so there is nothing to "
              "solve: " +
                  how + ", or pass --max-shots 0 to write the unlit scene");
}

}  // namespace rad
