// A light of the scene that is not a surface: a point, a spot or a directional light (the sun),
// as glTF's KHR_lights_punctual and the description format's Light objects give them.
#pragma once

#include <cstdint>
#include <memory>
#include <numbers>
#include <string>

#include "core/error.h"
#include "core/math.h"
#include "scene/photometry.h"

namespace rad {

enum class LightKind : uint8_t { Point, Spot, Directional };

const char* to_string(LightKind kind);

struct Light {
  std::string name;
  LightKind kind = LightKind::Point;
  SourceLoc loc;
  Vec3 position{0.0f};   // world, scene units (point, spot)
  Vec3 direction{0.0f};  // world, unit: where the light travels (spot axis; sun: toward the scene)
  Vec3 colour{1.0f};     // linear RGB factor
  /// Candela (point, spot) or lux (directional), as in KHR_lights_punctual.
  float intensity = 0.0f;
  /// Spot: half-angles of the cone, radians; full intensity within the inner, none beyond the
  /// outer, glTF's smooth falloff between.
  float inner_cone = 0.0f, outer_cone = std::numbers::pi_v<float> / 4.0f;
  /// Directional: the angular diameter of its disc, radians (the sun's, 0.53 degrees, by
  /// default): its shadows' penumbra.
  float angular_diameter = 0.53f * std::numbers::pi_v<float> / 180.0f;
  /// Point or spot: an IES distribution (null: the same `intensity` every way). Its nadir
  /// (gamma = 0) is `direction`, its C0 half-plane toward `photometric_up`; the candela it gives
  /// are multiplied by `intensity` (1 unless the description says otherwise).
  std::shared_ptr<const Photometry> photometry;
  /// World unit vector perpendicular to `direction`: the IES C = 0 reference direction (C = 90
  /// is cross(photometric_up, direction): counterclockwise seen from above a downlight).
  Vec3 photometric_up{1.0f, 0.0f, 0.0f};
  std::string group;  // light group name ("": the default group)
};

/// A unit vector perpendicular to `direction` (unit or not): world +X made perpendicular to it,
/// or +Z when the direction is within about 25 degrees of X. What photometric_up is by default.
Vec3 default_photometric_up(const Vec3& direction);

/// Refuses a light the solver cannot shoot, with its location and how to mend it: an intensity
/// that is negative, NaN or infinite; a negative or non-finite colour; a spot's or directional
/// light's zero-length (or non-finite) direction, or a light with photometry without one; a
/// spot's inner cone wider than its outer, or an outer cone beyond 90 degrees (or negative);
/// a directional light's angular diameter outside [0, 10) degrees; a non-finite position.
/// Throws rad::Error at light.loc.
void check_light(const Light& light);

/// The glTF KHR_lights_punctual spot falloff at the cosine `cos_angle` of the angle from the
/// axis: 1 within the inner cone, 0 beyond the outer, the square of the linear ramp between
/// (the extension's reference implementation, its ramp at least 0.001 in cosine wide).
float spot_falloff(float cos_angle, float inner_cone, float outer_cone);

/// Candela of a point or spot light toward world unit direction w: its IES table (times
/// `intensity`) or its `intensity`, the spot falloff included, before its colour. A directional
/// light's `intensity` (lux).
float intensity_toward(const Light& light, const Vec3& w);

}  // namespace rad
