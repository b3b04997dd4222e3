// Reference points no one can see: inside a solid of the scene (a shelf board's end sunk into
// a side panel, the floor under a box standing on it).
#pragma once

#include <cstdint>
#include <vector>

#include "reference/ray_scene.h"
#include "reference/reference_set.h"

namespace rad {

/// 1 for each point that lies inside a closed solid: the first surface met by every one of
/// seven rays leaving it (along its normal and six more at 60 degrees around it) is met from
/// behind. No light reaches such a point and none leaves it towards a viewer, so its radiosity
/// is 0 in the path tracer and undefined in any solver that interpolates over its element;
/// comparisons leave it out of their figures for visible points. `offset`: how far the rays
/// start off the surface (the solver's shadow offset of the scene).
std::vector<uint8_t> buried_points(const RayScene& scene, const Triangles& triangles,
                                   const std::vector<ReferencePoint>& points, float offset);

}  // namespace rad
