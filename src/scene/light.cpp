#include "scene/light.h"

#include <fmt/format.h>

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

Vec3 default_photometric_up(const Vec3& direction) {
  const float len = glm::length(direction);
  const Vec3 d = len > 0.0f ? direction / len : Vec3(0.0f, -1.0f, 0.0f);
  const Vec3 axis = std::abs(d.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 0.0f, 1.0f);
  return glm::normalize(axis - d * glm::dot(axis, d));
}

void check_light(const Light& l) {
  const std::string who = fmt::format("{} light \"{}\"", to_string(l.kind), l.name);
  const char* unit = l.kind == LightKind::Directional ? "lux" : "candela";
  if (!std::isfinite(l.intensity)) {
    throw Error(l.loc, fmt::format("{}: intensity {} is not a finite number: give its {} (0 or "
                                   "more)",
                                   who, l.intensity, unit));
  }
  if (l.intensity < 0.0f) {
    throw Error(l.loc, fmt::format("{}: negative intensity {:g}: give its {} (0 or more)", who,
                                   l.intensity, unit));
  }
  for (int k = 0; k < 3; ++k) {
    if (!(l.colour[k] >= 0.0f) || !std::isfinite(l.colour[k])) {
      throw Error(l.loc, fmt::format("{}: colour {:g} {:g} {:g}: each channel must be a finite "
                                     "factor of 0 or more (white is 1 1 1)",
                                     who, l.colour.x, l.colour.y, l.colour.z));
    }
  }
  if (l.kind != LightKind::Directional &&
      !(std::isfinite(l.position.x) && std::isfinite(l.position.y) &&
        std::isfinite(l.position.z))) {
    throw Error(l.loc, who + ": its position is not finite");
  }
  const bool needs_direction = l.kind != LightKind::Point || l.photometry != nullptr;
  const float len = glm::length(l.direction);
  if (needs_direction && !(len > 0.0f && std::isfinite(len))) {
    throw Error(l.loc, fmt::format("{}: its direction {:g} {:g} {:g} has {} length: give where it "
                                   "shines (e.g. <0 -1 0>, straight down in y-up)",
                                   who, l.direction.x, l.direction.y, l.direction.z,
                                   std::isfinite(len) ? "zero" : "no finite"));
  }
  constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;
  if (l.kind == LightKind::Spot) {
    if (!(l.inner_cone >= 0.0f) || !(l.outer_cone > 0.0f)) {
      throw Error(l.loc, fmt::format("{}: cone angles {:g} and {:g} degrees: the inner must be 0 "
                                     "or more and the outer above 0",
                                     who, l.inner_cone / kDeg, l.outer_cone / kDeg));
    }
    if (l.inner_cone > l.outer_cone) {
      throw Error(l.loc, fmt::format("{}: its inner cone ({:g} degrees) is wider than its outer "
                                     "({:g} degrees): full intensity within the inner, none "
                                     "beyond the outer; swap them",
                                     who, l.inner_cone / kDeg, l.outer_cone / kDeg));
    }
    if (l.outer_cone > std::numbers::pi_v<float> / 2.0f * (1.0f + 1e-6f)) {
      throw Error(l.loc, fmt::format("{}: its outer cone is {:g} degrees, beyond 90 (a half-angle "
                                     "from the axis): for light every way use a point light",
                                     who, l.outer_cone / kDeg));
    }
  }
  if (l.kind == LightKind::Directional &&
      !(l.angular_diameter >= 0.0f && l.angular_diameter < 90.0f * kDeg)) {
    throw Error(l.loc, fmt::format("{}: angular diameter {:g} degrees: give 0 (sharp shadows) to "
                                   "under 90 (the sun's is 0.53)",
                                   who, l.angular_diameter / kDeg));
  }
}

float intensity_toward(const Light& light, const Vec3& w) {
  if (light.kind == LightKind::Directional) return light.intensity;
  const float len = glm::length(light.direction);
  const float c = len > 0.0f ? glm::dot(w, light.direction) / len : 1.0f;
  float cd = light.intensity;
  if (light.photometry && len > 0.0f) {
    const DVec3 d = DVec3(light.direction) / double(len), dw(w);
    const DVec3 c0(light.photometric_up), c90 = glm::cross(c0, d);
    constexpr double kToDeg = 180.0 / std::numbers::pi;
    const double gamma = std::acos(std::clamp(glm::dot(dw, d), -1.0, 1.0)) * kToDeg;
    const double h = std::atan2(glm::dot(dw, c90), glm::dot(dw, c0)) * kToDeg;
    cd *= light.photometry->candela_at(float(gamma), float(h));
  }
  if (light.kind != LightKind::Spot) return cd;
  return cd * spot_falloff(c, light.inner_cone, light.outer_cone);
}

}  // namespace rad
