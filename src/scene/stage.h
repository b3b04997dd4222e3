// --stage: a model set on a grey floor under a soft area light scaled to its box, and with --sun
// a sun and a sky for an outdoor model, so that any model file gives a lit picture with no
// description written. Everything is placed relative to the model's box, so a model scaled or
// moved gives the same picture up to that scale.
#pragma once

#include <optional>
#include <string>

#include "core/aabb.h"
#include "core/math.h"

namespace rad {

struct SceneDescription;

/// Where the sun stands, in degrees: its elevation above the horizon, and its azimuth around
/// +y from +z (the side glTF models face and the stage camera looks from) toward +x.
struct SunAngles {
  float elevation_deg = 45.0f;
  float azimuth_deg = -45.0f;
};

/// "45,-45" (elevation, azimuth in degrees) -> SunAngles; empty text -> the defaults. Throws
/// rad::Error saying what --sun takes for anything else, an elevation outside (0, 90] or an
/// azimuth outside [-360, 360].
SunAngles parse_sun_angles(const std::string& text);

struct StageOptions {
  std::optional<SunAngles> sun;  // --sun: a directional light, the area light then a sky
};

/// The stage's reflectance, lights and their levels: one place for what the help, the summary
/// line and the documentation state.
inline constexpr float kStageFloorReflectance = 0.5f;
inline constexpr float kStageIlluminance = 1000.0f;       // lux under the light's centre, no sun
inline constexpr float kStageSkyIlluminance = 20000.0f;   // the same with --sun: the sky's share
inline constexpr float kStageSunIlluminance = 100000.0f;  // lux facing a clear day's sun

/// What was staged, in scene units: enough to print it, write it as a description, and frame it.
struct Stage {
  Aabb model;  // the model's box, which everything below is scaled to
  // The floor: a rectangle facing up at the model's lowest y, x and z from lo to hi.
  float floor_y = 0.0f;
  Vec2 floor_lo{0.0f}, floor_hi{0.0f};  // (x, z)
  // The light: a rectangle facing down above the model, emitting `exitance` (white).
  float light_y = 0.0f;
  Vec2 light_lo{0.0f}, light_hi{0.0f};  // (x, z)
  float exitance = 0.0f;
  float illuminance_below = 0.0f;  // what the light gives an unshaded floor under its centre
  std::optional<SunAngles> sun;
  Vec3 sun_direction{0.0f};  // where the sun's light travels (unit)
  float sun_illuminance = 0.0f;
  /// Unit vector from the model's centre toward where a camera sees it well: from the front
  /// (+z) and a little to the right (+x), from above, and below the light.
  Vec3 view_direction{0.0f};
};

/// The stage for a model whose box is `model`: a floor at its lowest y reaching beyond its
/// footprint (and its shadow in the sun), a light above it a little larger than its footprint,
/// at a height that keeps its light soft, emitting what gives `illuminance_below` under it.
/// Throws rad::Error when the box is empty or not finite.
Stage plan_stage(const Aabb& model, const StageOptions& options);

/// Adds the stage of plan_stage for the box of every triangle of `scene` (a model's scene, its
/// triangles placed) as a root Assembly "stage": Pures "stage floor" and "stage light", and the
/// Light "stage sun" with --sun; records it in scene.model->stage. Throws rad::Error naming the
/// file when the scene has no triangles.
Stage add_stage(SceneDescription& scene, const StageOptions& options);

/// One line saying what was staged, in numbers a description can repeat (the light's power
/// in lumens for `metres_per_unit` metres a scene unit).
std::string describe_stage(const Stage& stage, double metres_per_unit);

}  // namespace rad
