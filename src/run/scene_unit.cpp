#include "run/scene_unit.h"

#include <fmt/format.h>

#include "core/error.h"
#include "core/file_extension.h"
#include "hierarchy/auto_hierarchy.h"

namespace rad {

namespace {

bool is_gltf(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".gltf" || e == ".glb";
}

}  // namespace

double metres_per_unit(const SceneInput& in) {
  return in.unit && !is_gltf(in.path) ? *in.unit : 1.0;
}

void apply_scene_unit(Hierarchy& h, double metres_per_unit) {
  if (metres_per_unit == 1.0) return;
  const double per_square_unit = 1.0 / (metres_per_unit * metres_per_unit);
  for (Light& l : h.lights) {
    if (l.kind != LightKind::Directional) l.intensity = float(l.intensity * per_square_unit);
  }
}

Hierarchy load_scene(const SceneInput& in) {
  if (in.unit && is_gltf(in.path)) {
    warn(SourceLoc{in.path},
         fmt::format("--unit {} is ignored: glTF lengths are metres by the glTF specification; "
                     "leave --unit out for a glTF model",
                     *in.unit));
  }
  Hierarchy h = load_hierarchy(in.path, in.model, in.hierarchy);
  apply_scene_unit(h, metres_per_unit(in));
  return h;
}

}  // namespace rad
