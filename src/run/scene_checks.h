// What a scene must have for what was asked of it, checked in the run layer before any work:
// the light a solve shoots, and options that fit the kind of scene file.
#pragma once

#include "hierarchy/hierarchy.h"
#include "run/run_options.h"

namespace rad {

/// Refuses --emit and --stage for a description: the rules name a model's materials, and a
/// description's lamps carry an Emission line of their own, as its floor and lights are its
/// own objects. Throws rad::Error naming the file.
void check_scene_input(const SceneInput& in);

/// Whether any triangle of `h` with an area emits light.
bool emits_light(const Hierarchy& h);

/// Refuses a scene in which nothing emits light when the solve is to shoot (max_shots != 0):
/// there is nothing to solve. --max-shots 0 writes the unlit scene as it is. Throws rad::Error
/// naming the file and how to give it a light.
void require_light(const Hierarchy& h, const SceneInput& in, const SolverOptions& o);

}  // namespace rad
