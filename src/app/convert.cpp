#include "app/convert.h"

#include <cstdio>

#include "export/scene_export.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "run/scene_checks.h"
#include "scene/scene_file.h"
#include "scene/stage.h"

namespace rad {

int run_convert(const CommandLine& cmd) {
  check_scene_extension(cmd.converted);
  const SceneInput& in = cmd.job.input;
  check_scene_input(in);
  const HierarchyMode mode = in.hierarchy.value_or(HierarchyMode::AsRead);
  const SceneDescription scene = regroup(read_scene_file(in.path, in.model), mode);
  // A regrouped scene was built once already, and warned then.
  const Hierarchy h = build_hierarchy(scene, {}, /*warn=*/mode == HierarchyMode::AsRead);
  const std::vector<std::string> lost = write_scene_file(cmd.converted, scene, h);
  if (!cmd.run.quiet) {
    size_t pures = 0;
    for (const SceneObject& o : h.objects) pures += o.kind == ObjectKind::Pure;
    std::printf("%s: %zu objects (%zu Pures), %zu triangles\n", cmd.converted.c_str(),
                h.objects.size(), pures, h.triangles.size());
    if (h.model && h.model->stage)
      std::printf("%s\n", describe_stage(*h.model->stage, 1.0).c_str());
    for (const std::string& l : lost) std::printf("note: %s\n", l.c_str());
  }
  return 0;
}

}  // namespace rad
