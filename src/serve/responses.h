// What the server sends back: the scene and snapshot status as JSON, and the mesh and its
// colours as little-endian binary buffers the page views as typed arrays.
#pragma once

#include <string>

#include "export/camera.h"
#include "hierarchy/hierarchy.h"
#include "serve/snapshot.h"

namespace rad {

/// Binary buffers start with 8 little-endian uint32: magic, version, mesh version, vertex count,
/// index count (0 in a colour buffer), then 3 zeros; every array after it is 4-byte aligned.
inline constexpr uint32_t kMeshMagic = 0x4d444152;    // "RADM"
inline constexpr uint32_t kColourMagic = 0x43444152;  // "RADC"

/// The static description of the scene: name, objects (id, name, kind, parent, children,
/// triangle range), the lights (id, name, kind, intensity unit, whether the page may change it,
/// position and direction), bounds, the default camera, the largest emission in the scene, the
/// solver's convergence goal.
std::string scene_json(const Hierarchy& h, const Camera& camera, double converge);

/// The snapshot without its arrays: versions, status, progress, exposure, per-object elements
/// and controls, per-light colour and intensity, convergence history, notice.
std::string status_json(const Hierarchy& h, const Snapshot& s);

/// Header, positions (3 float per vertex), colours (3 float per vertex), indices (uint32),
/// face polygons (int32 per face): one buffer, so they always come from the same snapshot.
std::string mesh_buffer(const Snapshot& s);

/// Header and colours (3 float per vertex) only.
std::string colour_buffer(const Snapshot& s);

}  // namespace rad
