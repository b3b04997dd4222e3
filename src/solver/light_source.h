// A light of the scene (scene/light.h) as a shooter of the progressive solver: it shoots once,
// before any surface, its direct light reaching every vertex in front of it.
#pragma once

#include <cstdint>

#include "core/aabb.h"
#include "solver/shot_source.h"

namespace rad {

/// Shadow rays toward a directional light's disc (the sun: 0.53 degrees by default): its
/// penumbra is their mean.
inline constexpr size_t kSunRays = 16;

/// The intensity a light's shots are in units of (ShotSource::light_colour and the energy's
/// light_unshot multiply it): the scene's, or 1 for a light the scene gives intensity 0, so that
/// an edit can still turn that one on.
inline float light_unit(const Light& l) { return l.intensity > 0.0f ? l.intensity : 1.0f; }

/// A light of the scene as it shoots: with its light_unit intensity.
inline Light shooting_light(Light l) {
  l.intensity = light_unit(l);
  return l;
}

/// The scene's lights as they shoot (shooting_light).
std::vector<Light> shooting_lights(const std::vector<Light>& lights);

/// Light `index` of `lights` (shooting_lights) frozen as the source of a shot that shoots `colour`
/// (per channel: the light's colour, or an edit's change of it). `bounds` is the scene's box: a
/// directional light's rays end beyond it.
ShotSource make_light_source(const std::vector<Light>& lights, int32_t index, const Vec3& colour,
                             const Aabb& bounds);

/// The illuminance (lux with candela and metres; without shadows) that `src`, a light, gives a
/// point x with unit normal n, per unit of its colour: I(w) cos / r^2 for a point or spot light
/// (w from the light toward x), E cos for a directional one. 0 behind the point's plane.
float light_illuminance(const ShotSource& src, const Vec3& x, const Vec3& n);

/// Where the shadow ray from x (moved off its surface) toward the light ends: the light's
/// position, or for a directional light the point `sun_reach` away toward sun direction k.
inline Vec3 light_ray_end(const ShotSource& src, const Vec3& x, size_t k) {
  return src.emitter->kind == LightKind::Directional ? x + src.sun_directions[k] * src.sun_reach
                                                     : src.emitter->position;
}

/// How many shadow rays a point's gain from the light takes (1, or kSunRays for the sun).
inline size_t light_ray_count(const ShotSource& src) {
  return src.emitter->kind == LightKind::Directional ? src.sun_directions.size() : 1;
}

/// The light's power (mean over its colour's channels, in lumens with candela) that reaches as
/// far as the scene's box `bounds` could take: all of a point or spot light's (its intensity
/// integrated over the sphere), and a directional light's illuminance over the box's shadow
/// across its direction. What the solver's relative limits and its convergence scale with.
double light_power(const Light& light, const Aabb& bounds);

/// False when no point of the triangle with corners c and unit normal n can receive from the
/// light: it lies wholly behind the light, or faces away from the sun.
bool light_reaches(const ShotSource& src, const std::array<Vec3, 3>& c, const Vec3& n);

}  // namespace rad
