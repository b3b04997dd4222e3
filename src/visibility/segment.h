// The one visibility contract every backend shares: shadow segments and their epsilons.
#pragma once

#include "core/aabb.h"
#include "core/math.h"

namespace rad {

/// A shadow segment: the points origin + t * direction for t in the open interval (0, 1).
/// Any triangle crossing it there occludes it; hits at exactly t = 0 or t = 1 are unspecified,
/// which is why make_shadow_segment moves both ends off their surfaces.
struct Segment {
  Vec3 origin;
  Vec3 direction;  // unnormalised: origin + direction is the far end
};

/// The solver's batch: segments from one receiving point to many source points, the far ends as
/// three coordinate arrays. Segment i runs from `origin` to (x[i], y[i], z[i]); both ends are
/// already moved off their surfaces (off_surface).
struct SegmentFan {
  Vec3 origin;
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  size_t size = 0;
  Segment segment(size_t i) const { return {origin, Vec3(x[i], y[i], z[i]) - origin}; }
};

/// Distance by which both ends of a shadow segment leave their surfaces, scaled to the scene
/// (a fixed fraction of the bounding-box diagonal) so it is far above float rounding of the
/// coordinates and far below any feature size.
float shadow_offset(const Aabb& scene_bounds);

/// A segment end: point p moved `offset` along `normal` (towards the side it faces).
inline Vec3 off_surface(const Vec3& p, const Vec3& normal, float offset) {
  return p + normal * offset;
}

/// Segment from a receiving point (with its surface normal) to a point on a source (with the
/// source's normal), each end moved off its surface.
inline Segment make_shadow_segment(const Vec3& from, const Vec3& from_normal, const Vec3& to,
                                   const Vec3& to_normal, float offset) {
  const Vec3 a = off_surface(from, from_normal, offset);
  return {a, off_surface(to, to_normal, offset) - a};
}

}  // namespace rad
