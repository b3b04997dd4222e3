// --unit: how long a scene unit is, for what rad reports in physical units. glTF lengths are
// metres by its specification; a description, OBJ or PLY file is in metres per --unit.
#pragma once

#include "hierarchy/hierarchy.h"
#include "run/run_options.h"

namespace rad {

/// Metres per scene unit of `in`: its --unit (1 without), or 1 for a glTF model, whose lengths
/// are metres whatever --unit says.
double metres_per_unit(const SceneInput& in);

/// Makes the solve, which measures every length in scene units, light the scene as it would in
/// metres: a point or spot light of I candela gives I / (r u)^2 lux at r scene units, so its
/// intensity (or its IES table's factor) becomes I / u^2. Nothing else a solve computes depends
/// on the length of a unit: form factors between surfaces and a directional light's lux do not.
void apply_scene_unit(Hierarchy& h, double metres_per_unit);

/// load_hierarchy (hierarchy/auto_hierarchy.h) for `in`, lit for its unit (apply_scene_unit).
/// Warns, at the file, that --unit is ignored for a glTF model. Throws rad::Error as
/// load_hierarchy does.
Hierarchy load_scene(const SceneInput& in);

}  // namespace rad
