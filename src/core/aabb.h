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
  /// The larger of the diagonal and the largest coordinate magnitude: float rounding of the
  /// positions inside the box scales with it (about 1.2e-7 of it), not with the diagonal alone.
  float magnitude() const {
    if (empty()) return 0.0f;
    return std::max(diagonal(), std::max(max_component(glm::abs(lo)), max_component(glm::abs(hi))));
  }
};

/// The box of a triangle's corners.
inline Aabb triangle_box(const std::array<Vec3, 3>& c) {
  Aabb b;
  for (const Vec3& p : c) b.extend(p);
  return b;
}

}  // namespace rad
