#include "scene/light.h"

#include <algorithm>
#include <cmath>

namespace rad {

const char* to_string(LightKind kind) {
  switch (kind) {
    case LightKind::Point:
      return "point";
    case LightKind::Spot:
      return "spot";
    case LightKind::Directional:
      return "directional";
  }
  return "?";
}

float spot_falloff(float cos_angle, float inner_cone, float outer_cone) {
  const float cos_outer = std::cos(outer_cone);
  const float scale = 1.0f / std::max(0.001f, std::cos(inner_cone) - cos_outer);
  const float t = std::clamp((cos_angle - cos_outer) * scale, 0.0f, 1.0f);
  return t * t;
}

float intensity_toward(const Light& light, const Vec3& w) {
  if (light.kind != LightKind::Spot) return light.intensity;
  const float len = glm::length(light.direction);
  const float c = len > 0.0f ? glm::dot(w, light.direction) / len : 1.0f;
  return light.intensity * spot_falloff(c, light.inner_cone, light.outer_cone);
}

}  // namespace rad
