// Closest-hit and occlusion rays against a scene's triangles, for the reference path tracer
// (Embree 3 behind this interface; <embree3/rtcore.h> stays in ray_scene.cpp).
#pragma once

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cstdint>
#include <memory>

#include "hierarchy/hierarchy.h"

namespace rad {

/// Sets flush-to-zero and denormals-are-zero for its scope (Embree wants both on every thread
/// that traces) and restores the caller's mode afterwards.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(_mm_getcsr()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
};

/// The nearest triangle along a ray: its index (-1 if none), distance in units of the ray's
/// direction, and barycentric coordinates (u, v) of b and c.
struct RayHit {
  int32_t triangle = -1;
  float t = 0.0f;
  float u = 0.0f, v = 0.0f;
};

/// One Embree BVH over all triangles of a hierarchy (triangle index = primitive id), both faces
/// hit. A triangle of a cut-out Pure (an alpha mask, and texture coordinates) is met only where
/// its mask is opaque, the test rad's visibility backends make (scene/texture.h opaque_at).
/// Immutable after construction; safe to query from many threads (each under FlushDenormals).
class RayScene {
 public:
  /// Keeps pointers into `h`'s objects (their masks), which must outlive the scene. Throws
  /// rad::Error if Embree fails.
  explicit RayScene(const Hierarchy& h);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Nearest hit of origin + s dir for s in (0, tfar).
  RayHit intersect(const Vec3& origin, const Vec3& dir, float tfar) const;
  /// Nearest front-face hit (the ray meets the triangle's front side) for s in (0, tfar).
  RayHit intersect_front(const Vec3& origin, const Vec3& dir, float tfar) const;
  /// True if any triangle meets origin + s dir for s in (0, tfar).
  bool occluded(const Vec3& origin, const Vec3& dir, float tfar) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad
