// What the page edits for a Pure: colour, reflectivity and emission, as the description writes
// them (design §2: reflectance = Reflectivity x Color, emission = Emission x Color); and for a
// light (scene/light.h): its colour and intensity.
#pragma once

#include <optional>
#include <string>

#include "scene/description.h"
#include "scene/light.h"
#include "solver/solution.h"

namespace rad {

/// Largest emission a request may set (radiant exitance, scene units): finite and far above any
/// light the bundled scenes use, so a typo cannot flood the solve with infinities.
inline constexpr float kMaxEmission = 1e7f;

struct MaterialControls {
  Vec3 colour{1.0f};          // each channel in [0, 1]
  float reflectivity = 0.0f;  // in [0, 1]
  float emission = 0.0f;      // in [0, kMaxEmission]

  bool operator==(const MaterialControls&) const = default;
};

/// Some of the three controls; the others keep their current values.
struct MaterialPatch {
  std::optional<Vec3> colour;
  std::optional<float> reflectivity;
  std::optional<float> emission;
};

/// Splits a material into controls. The colour is normalised so its largest channel is 1 (taken
/// from the emission when there is one, else from the reflectance); reflectivity and emission
/// are then the factors along that channel, so to_material(to_controls(m)) == m whenever the
/// reflectance and the emission share a colour, as every parsed description does. Black gives
/// white colour, reflectivity 0, emission 0.
MaterialControls to_controls(const Material& m);

/// reflectance = reflectivity x colour, emission = emission x colour.
Material to_material(const MaterialControls& c);

/// `c` with the patch's fields replaced.
MaterialControls apply_patch(MaterialControls c, const MaterialPatch& p);

/// Empty when every control is in range; else a sentence naming the first one that is not.
std::optional<std::string> controls_error(const MaterialControls& c);

/// Largest intensity a request may give a light (candela or lux): far above any luminaire's or
/// the sun's, finite so a typo cannot flood the solve with infinities.
inline constexpr float kMaxLightIntensity = 1e9f;

/// A light's colour and intensity as the page shows them: the intensity in candela (point and
/// spot lights) or lux (directional), whatever the scene's unit of length.
struct LightControls {
  Vec3 colour{1.0f};       // each channel in [0, 1]
  float intensity = 0.0f;  // in [0, kMaxLightIntensity]; 0: off

  bool operator==(const LightControls&) const = default;
};

struct LightPatch {
  std::optional<Vec3> colour;
  std::optional<float> intensity;
};

/// "cd" for a point or spot light, "lx" for a directional one.
const char* intensity_unit(LightKind kind);

/// A light's controls: its colour with the largest channel brought to at most 1 (the intensity
/// taking the rest, so colour x intensity is kept), its intensity in candela for
/// `square_metres_per_square_unit` (the hierarchy holds a point or spot light's candela per
/// square scene unit: run/scene_unit.h).
LightControls to_light_controls(const Light& l, double square_metres_per_square_unit);

/// The colour and intensity the solver takes (solver/edits.h's set_light), in the hierarchy's
/// units: the inverse of to_light_controls.
LightSetting to_light_setting(const LightControls& c, LightKind kind,
                              double square_metres_per_square_unit);

LightControls apply_patch(LightControls c, const LightPatch& p);

/// Empty when the controls are in range; else a sentence naming the first one that is not.
std::optional<std::string> controls_error(const LightControls& c);

}  // namespace rad
