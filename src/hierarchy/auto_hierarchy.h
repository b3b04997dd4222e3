// The hierarchy of design §3 built automatically (design §8): what a model file gets, and a
// description on request (--hierarchy auto).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "hierarchy/hierarchy.h"
#include "scene/model_scene.h"

namespace rad {

enum class HierarchyMode : uint8_t {
  AsRead,     // the description's objects as written; a model's Assembly > groups > Pures
  Automatic,  // the Pures regrouped: compact Composites, Assemblies of what is near
  Flat,       // every Pure in one Composite (one grid over the scene: a baseline to measure)
};

/// "file" | "auto" | "flat"; throws rad::Error otherwise.
HierarchyMode parse_hierarchy_mode(const std::string& text);
const char* to_string(HierarchyMode mode);

/// The mode a scene gets when none is asked: Automatic for a model (its groups are whatever the
/// modelling tool left: a thousand-object OBJ is one flat list), AsRead for a description.
HierarchyMode default_hierarchy_mode(const std::string& scene_path);

/// The Pures of `h` (name, material, placed triangles, flags resolved onto each) regrouped by a
/// top-down split of their boxes: a group of at most 32 Pures whose boxes fill at least a
/// quarter of its own box (little empty space, design §3), none of them more than half of it (a
/// room's shell is not a part of the chairs inside it) nor more than 4 times as dense in
/// triangles as the group (a finely tessellated plant beside a sofa would crowd a few cells of
/// one grid), becomes a Composite (a chair: one grid over its parts); any other group is split in
/// two at the median of its Pures' centres along their widest spread and becomes an Assembly of the
/// halves (so a shadow ray tests O(log n) boxes, not n). Deterministic. Throws rad::Error if the
/// scene has Lights lists, which name objects that regrouping does not keep.
SceneDescription automatic_hierarchy(const Hierarchy& h);

/// Every Pure of `h` in one Composite.
SceneDescription flat_hierarchy(const Hierarchy& h);

/// The scene regrouped as `mode` says (AsRead: as it is).
SceneDescription regroup(const SceneDescription& scene, HierarchyMode mode);

/// build_hierarchy(regroup(scene, mode)) made without building twice: h regrouped as `mode`
/// says, its triangles (with their normals and areas) reordered for the new tree.
Hierarchy regrouped_hierarchy(const Hierarchy& h, HierarchyMode mode);

/// build_hierarchy(regroup(scene, mode)).
Hierarchy build_hierarchy(const SceneDescription& scene, HierarchyMode mode);

/// The scene a path names (scene_file.h) with its hierarchy: what every mode of rad solves.
/// `mode` unset: default_hierarchy_mode(path).
Hierarchy load_hierarchy(const std::string& path, const ModelOptions& model,
                         std::optional<HierarchyMode> mode);

}  // namespace rad
