// Backend agreement at the ray level: random shadow segments over a scene, each backend's answer
// against an oracle's (brute force), every mismatch classified by how near the segment passes
// to changing its answer. Used by `rad --cross-check` and by the cross-check tests.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "visibility/backend.h"

namespace rad {

/// n segments over the scene, a third of each kind: surface point to surface point with the
/// solver's offsets (the rays it casts), anywhere to anywhere in the box enlarged by 10%, and
/// surface point to near a random triangle (dense spots, edges and corners). Same seed, same
/// segments.
std::vector<Segment> random_segments(const Hierarchy& h, size_t n, uint32_t seed);

/// How close segment s comes to changing its answer for any triangle: the least distance from
/// it to a triangle edge, or from one of its ends to a triangle (in double; O(triangles)).
/// Moving both ends by less than this cannot make it enter or leave any triangle.
double ambiguity_distance(const Hierarchy& h, const Segment& s);

/// Closer than this to changing its answer, float rounding may decide either way: 1e-6 of the
/// scene's magnitude (Aabb::magnitude: about 8 float ulps of its coordinates).
double ambiguity_limit(const Hierarchy& h);

struct RayMismatch {
  Segment segment;
  uint8_t expected = 0, got = 0;  // 1 = blocked
  double ambiguity = 0.0;         // ambiguity_distance
};

struct RayAgreement {
  size_t segments = 0;
  size_t blocked = 0;  // by the oracle
  size_t near = 0;     // mismatches within ambiguity_limit: rounding
  size_t far = 0;      // mismatches beyond it: a bug
  double worst_near = 0.0, worst_far = 0.0;
  std::vector<RayMismatch> mismatches;  // all of them, in segment order
};

/// Every segment's answer from `backend` against `oracle`'s (in parallel).
RayAgreement compare_rays(const Hierarchy& h, const VisibilityBackend& oracle,
                          const VisibilityBackend& backend, std::span<const Segment> segments);

}  // namespace rad
