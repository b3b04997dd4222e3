#include "solver/light_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "core/planar_geometry.h"

namespace rad {

namespace {

// A light's axis: its direction (unit from every reader), or straight down for a point light
// given none.
Vec3 axis_of(const Light& l) {
  return l.direction != Vec3(0.0f) ? l.direction : Vec3(0.0f, -1.0f, 0.0f);
}

// Two unit vectors completing the unit vector a to an orthonormal frame.
void frame(const Vec3& a, Vec3& e1, Vec3& e2) {
  DVec3 u, w;
  plane_frame(DVec3(a), u, w);
  e1 = Vec3(u), e2 = Vec3(w);
}

}  // namespace

std::vector<Light> shooting_lights(const std::vector<Light>& lights) {
  std::vector<Light> at_unit;
  at_unit.reserve(lights.size());
  for (const Light& l : lights) at_unit.push_back(shooting_light(l));
  return at_unit;
}

ShotSource make_light_source(const std::vector<Light>& lights, int32_t index, const Vec3& colour,
                             const Aabb& bounds) {
  assert(index >= 0 && size_t(index) < lights.size());
  const Light& l = lights[size_t(index)];
  ShotSource src;
  src.light = index;
  src.light_colour = colour;
  src.emitter = &l;
  src.planar = false;
  src.major = true;
  if (l.kind == LightKind::Directional) {
    // Toward the sun: its disc's points spread by area (a Vogel spiral: ring k at radius
    // sqrt((k + 1/2) / n), turned by the golden angle), each direction as far off the centre as
    // its point lies on the disc.
    const Vec3 toward = -l.direction;
    Vec3 e1, e2;
    frame(toward, e1, e2);
    const float radius = std::tan(0.5f * l.angular_diameter);
    const size_t n = radius > 0.0f ? kSunRays : 1;
    const float golden = std::numbers::pi_v<float> * (3.0f - std::sqrt(5.0f));
    for (size_t k = 0; k < n; ++k) {
      const float r = radius * std::sqrt((float(k) + 0.5f) / float(n));
      const float a = golden * float(k);
      src.sun_directions.push_back(
          glm::normalize(toward + e1 * (r * std::cos(a)) + e2 * (r * std::sin(a))));
    }
    // Past the far side of the scene's box from any point in it.
    src.sun_reach = 2.0f * std::max(bounds.diagonal(), 1e-3f);
    src.box = bounds;
    src.centroid = bounds.center() + toward * src.sun_reach;
    src.axis = -toward;
    src.extent = bounds.diagonal();
  } else {
    src.box.extend(l.position);
    src.centroid = l.position;
    src.axis = axis_of(l);
  }
  return src;
}

float light_illuminance(const ShotSource& src, const Vec3& x, const Vec3& n) {
  const Light& l = *src.emitter;
  if (l.kind == LightKind::Directional) {
    const float c = -glm::dot(n, src.axis);
    return c > 0.0f ? l.intensity * c : 0.0f;
  }
  const Vec3 d = l.position - x;
  const float r2 = glm::dot(d, d);
  if (!(r2 > 0.0f)) return 0.0f;
  const float r = std::sqrt(r2);
  const float c = glm::dot(n, d) / r;
  if (!(c > 0.0f)) return 0.0f;
  return intensity_toward(l, -d / r) * c / r2;
}

double light_power(const Light& l, const Aabb& bounds) {
  if (l.kind == LightKind::Directional) {
    // E times the area of the box's shadow across the direction.
    const Vec3 d = l.direction;
    const Vec3 e = bounds.empty() ? Vec3(0.0f) : bounds.extent();
    const double shadow = std::abs(double(d.x)) * e.y * e.z + std::abs(double(d.y)) * e.x * e.z +
                          std::abs(double(d.z)) * e.x * e.y;
    return double(l.intensity) * shadow;
  }
  // The intensity integrated over the sphere by the midpoint rule, in a frame whose pole is the
  // light's axis (a spot's cone and an IES table are finest in polar angle).
  const Vec3 axis = axis_of(l);
  Vec3 e1, e2;
  frame(axis, e1, e2);
  constexpr int kPolar = 180, kAzimuth = 72;
  const double dt = std::numbers::pi / kPolar, dp = 2.0 * std::numbers::pi / kAzimuth;
  double sum = 0.0;
  for (int i = 0; i < kPolar; ++i) {
    const double t = (i + 0.5) * dt, st = std::sin(t), ct = std::cos(t);
    double ring = 0.0;
    for (int j = 0; j < kAzimuth; ++j) {
      const double p = (j + 0.5) * dp;
      const Vec3 w = axis * float(ct) + e1 * float(st * std::cos(p)) + e2 * float(st * std::sin(p));
      ring += double(intensity_toward(l, w));
    }
    sum += ring * st * dt * dp;
  }
  return sum;
}

bool light_reaches(const ShotSource& src, const std::array<Vec3, 3>& c, const Vec3& n) {
  const Light& l = *src.emitter;
  if (l.kind == LightKind::Directional) return glm::dot(n, src.axis) < 0.0f;
  return glm::dot(l.position - c[0], n) > 0.0f;
}

}  // namespace rad
