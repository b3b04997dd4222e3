// Writing a scene back as a description file (design §2): what rad-gen, rad-tessellate and
// rad convert write.
#pragma once

#include <ostream>

#include "scene/description.h"

namespace rad {

/// Writes the scene as a description file with every Pure's triangles in a Data block,
/// copies, transforms and flags as written. Reflectance and emission are written as
/// Reflectivity × Color and Emission × Color; Light objects with their properties (an IES file
/// by its absolute path).
void write_description(const SceneDescription& scene, std::ostream& out);

/// Whether `m` survives the description format as it is: one Color serves reflectance and
/// emission, so an emission whose colour differs from the reflectance's cannot be written.
bool material_is_writable(const Material& m);

}  // namespace rad
