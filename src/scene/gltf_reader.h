// glTF 2.0 scenes (.gltf with its buffers, or .glb), through tinygltf.
#pragma once

#include <string>
#include <string_view>

#include "scene/model.h"

namespace rad {

/// The default scene's triangles in world space: node transforms composed down the tree, a mesh
/// placed by several nodes flattened once per placement (one group each, named after the node).
/// Materials: baseColorFactor times the mean linear colour of the base colour texture,
/// emissiveFactor times KHR_materials_emissive_strength; primitives without a material get the
/// glTF default (white, reflectance 1, clamped later). Triangle, strip and fan primitives are
/// read; points and lines skipped with a warning, and so, once each, what rad does not render:
/// skins, animations, extensions it does not read, BLEND (read as MASK at 0.5), COLOR_0, and
/// textured triangles without their coordinates. Every accessor is checked against its buffer.
/// `folder` is where external buffers and images are looked for ("" refuses them). Throws
/// rad::Error naming the file.
Model parse_gltf(std::string_view bytes, const std::string& path, const std::string& folder);

Model read_gltf_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
