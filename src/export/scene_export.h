// A scene itself (geometry, materials, hierarchy; not a solution) written in another format:
// what rad convert writes.
#pragma once

#include <string>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "scene/description.h"

namespace rad {

/// Throws rad::Error unless rad writes scenes with this path's extension (.des, .obj, .gltf,
/// .glb, .ply).
void check_scene_extension(const std::string& path);

/// Writes the scene to `path` in the format its extension names, atomically:
/// - .des: the description as parsed (copies, transforms, flags and hierarchy as written);
/// - .obj: a group per Pure, named by its path in the hierarchy, with a material of its own in
///   an .mtl file beside it (Kd reflectance, Ke emission);
/// - .gltf / .glb: a node per object of the hierarchy, a mesh per Pure with its material
///   (baseColorFactor, emissiveFactor x KHR_materials_emissive_strength);
/// - .ply: the triangles, with the reflectance as vertex colours (PLY has no materials).
/// Every format but .des gets the placed triangles of `h` (copies and transforms applied).
/// Returns one line for each kind of information the target format could not hold.
std::vector<std::string> write_scene_file(const std::string& path, const SceneDescription& scene,
                                          const Hierarchy& h);

}  // namespace rad
