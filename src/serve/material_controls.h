// What the page edits for a Pure: colour, reflectivity and emission, as the description writes
// them (design §2: reflectance = Reflectivity x Color, emission = Emission x Color).
#pragma once

#include <optional>
#include <string>

#include "scene/description.h"

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

}  // namespace rad
