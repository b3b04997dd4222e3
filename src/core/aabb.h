// Axis-aligned bounding box.
#pragma once

#include <algorithm>
#include <array>
#include <limits>

#include "core/math.h"

namespace rad {

struct Aabb {
  Vec3 lo{std::numeric_limits<float>::infinity()};
  Vec3 hi{-std::numeric_limits<float>::infinity()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  Vec3 extent() const { return empty() ? Vec3(0.0f) : hi - lo; }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  float diagonal() const { return glm::length(extent()); }
  /// The axis along which the box is widest (0, 1, 2 for x, y, z), the lowest of equals: where
  /// the median splits of clusters, strata and trees cut.
  int widest_axis() const {
    const Vec3 e = extent();
    return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  }
  /// The larger of the diagonal and the largest coordinate magnitude: float rounding of the
  /// positions inside the box scales with it (about 1.2e-7 of it), not with the diagonal alone.
  float magnitude() const {
    if (empty()) return 0.0f;
    return std::max(diagonal(), std::max(max_component(glm::abs(lo)), max_component(glm::abs(hi))));
  }
};

/// How far the box's highest point lies above the plane through `origin` with normal `n`
/// (negative: the whole box below it).
inline float highest_above(const Aabb& b, const Vec3& origin, const Vec3& n) {
  return glm::dot(b.center() - origin, n) + glm::dot(b.extent() * 0.5f, glm::abs(n));
}

/// How far the box's lowest point lies above that plane.
inline float lowest_above(const Aabb& b, const Vec3& origin, const Vec3& n) {
  return glm::dot(b.center() - origin, n) - glm::dot(b.extent() * 0.5f, glm::abs(n));
}

/// The squared distance between two boxes (0 where they meet).
inline float distance2(const Aabb& a, const Aabb& b) {
  const Vec3 gap = glm::max(glm::max(a.lo - b.hi, b.lo - a.hi), Vec3(0.0f));
  return glm::dot(gap, gap);
}

/// The squared distance from a box to a point (0 inside it).
inline float distance2(const Aabb& a, const Vec3& p) {
  const Vec3 gap = glm::max(glm::max(a.lo - p, p - a.hi), Vec3(0.0f));
  return glm::dot(gap, gap);
}

/// The box of a triangle's corners.
inline Aabb triangle_box(const std::array<Vec3, 3>& c) {
  Aabb b;
  for (const Vec3& p : c) b.extend(p);
  return b;
}

}  // namespace rad
