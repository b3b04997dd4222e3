#include "serve/material_controls.h"

#include <fmt/format.h>

#include <cmath>

namespace rad {

MaterialControls to_controls(const Material& m) {
  MaterialControls c;
  const float e = max_component(m.emission), rho = max_component(m.reflectance);
  const Vec3 base = e > 0.0f ? m.emission : m.reflectance;
  const float top = e > 0.0f ? e : rho;
  if (!(top > 0.0f)) return c;  // black: white, reflectivity 0, emission 0
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (base[i] > base[k]) k = i;
  }
  c.colour = glm::clamp(base / top, Vec3(0.0f), Vec3(1.0f));
  c.colour[k] = 1.0f;
  c.emission = e;
  c.reflectivity = m.reflectance[k];
  return c;
}

Material to_material(const MaterialControls& c) {
  return Material{c.colour * c.reflectivity, c.colour * c.emission};
}

MaterialControls apply_patch(MaterialControls c, const MaterialPatch& p) {
  if (p.colour) c.colour = *p.colour;
  if (p.reflectivity) c.reflectivity = *p.reflectivity;
  if (p.emission) c.emission = *p.emission;
  return c;
}

std::optional<std::string> controls_error(const MaterialControls& c) {
  for (int k = 0; k < 3; ++k) {
    if (!(c.colour[k] >= 0.0f && c.colour[k] <= 1.0f)) {
      return fmt::format("colour channel {} is {}; it must be in [0, 1]", k, c.colour[k]);
    }
  }
  if (!(c.reflectivity >= 0.0f && c.reflectivity <= 1.0f)) {
    return fmt::format("reflectivity is {}; it must be in [0, 1]", c.reflectivity);
  }
  if (!(c.emission >= 0.0f && c.emission <= kMaxEmission)) {
    return fmt::format("emission is {}; it must be in [0, {:g}]", c.emission, kMaxEmission);
  }
  return std::nullopt;
}

const char* intensity_unit(LightKind kind) { return kind == LightKind::Directional ? "lx" : "cd"; }

LightControls to_light_controls(const Light& l, double square_metres_per_square_unit) {
  LightControls c;
  double intensity = double(l.intensity);
  if (l.kind != LightKind::Directional) intensity *= square_metres_per_square_unit;
  const float top = max_component(l.colour);
  c.colour = l.colour;
  if (top > 1.0f) {
    c.colour = glm::min(l.colour / top, Vec3(1.0f));
    intensity *= double(top);
  }
  c.intensity = float(intensity);
  return c;
}

LightSetting to_light_setting(const LightControls& c, LightKind kind,
                              double square_metres_per_square_unit) {
  double intensity = double(c.intensity);
  if (kind != LightKind::Directional) intensity /= square_metres_per_square_unit;
  return {c.colour, float(intensity)};
}

LightControls apply_patch(LightControls c, const LightPatch& p) {
  if (p.colour) c.colour = *p.colour;
  if (p.intensity) c.intensity = *p.intensity;
  return c;
}

std::optional<std::string> controls_error(const LightControls& c) {
  for (int k = 0; k < 3; ++k) {
    if (!(c.colour[k] >= 0.0f && c.colour[k] <= 1.0f)) {
      return fmt::format("colour channel {} is {}; it must be in [0, 1]", k, c.colour[k]);
    }
  }
  if (!(c.intensity >= 0.0f && c.intensity <= kMaxLightIntensity)) {
    return fmt::format("intensity is {}; it must be in [0, {:g}]", c.intensity, kMaxLightIntensity);
  }
  return std::nullopt;
}

}  // namespace rad
