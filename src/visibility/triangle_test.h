// Precomputed triangle records and the segment–triangle test of design §6 (barycentrics via s_a,
// s_b).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/math.h"
#include "hierarchy/hierarchy.h"
#include "visibility/backend.h"

// The test relies on IEEE comparisons: a NaN or infinite t (parallel segments, padding lanes)
// must fail 0 < t < 1.
#if defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__)
#error "visibility/triangle_test.h needs IEEE NaN and infinity semantics (no -ffast-math)"
#endif

namespace rad {

/// The nearest hit found so far along a segment (first_hit of the backends).
struct SegmentHitRecord {
  float t = std::numeric_limits<float>::infinity();
  uint32_t triangle = ~0u;
};

/// One triangle a, b, c prepared for the design §6 test, 64 bytes (one cache line):
/// e_a = a − c, e_b = b − c, n = e_a × e_b, plane n·p = plane_offset,
/// s_a = e_b × n / |n|², s_b = n × e_a / |n|² (= e_a × (e_b × e_a) / |n|²), so that any p on the
/// plane is c + α e_a + β e_b with α = (p − c)·s_a, β = (p − c)·s_b. A degenerate triangle
/// (n = 0) gets all-zero vectors and is never hit.
struct alignas(16) TriangleRecord {
  Vec3 normal{0.0f};  // n = e_a × e_b, unnormalised
  float plane_offset = 0.0f;
  Vec3 s_a{0.0f};
  uint32_t cutout = 0;  // a cut-out triangle: 1 + its index in the backend's Cutouts; else 0
  Vec3 s_b{0.0f};
  float pad1 = 0.0f;
  Vec3 c{0.0f};
  float pad2 = 0.0f;
};
static_assert(sizeof(TriangleRecord) == 64);

/// Computes the record in double and rounds once to float.
inline TriangleRecord make_triangle_record(const std::array<Vec3, 3>& t) {
  DVec3 a(t[0]), b(t[1]), c(t[2]);
  DVec3 e_a = a - c, e_b = b - c;
  DVec3 n = glm::cross(e_a, e_b);
  double n2 = glm::dot(n, n);
  TriangleRecord r;
  r.c = Vec3(c);
  if (!(n2 > 0.0)) return r;
  r.normal = Vec3(n);
  r.plane_offset = float(glm::dot(n, c));
  r.s_a = Vec3(glm::cross(e_b, n) / n2);
  r.s_b = Vec3(glm::cross(n, e_a) / n2);
  return r;
}

/// The cut-out triangles a backend traces: each one's texture coordinates (at a, b, c) and its
/// Pure's mask (copied: a backend keeps nothing of the hierarchy it was built from).
struct Cutouts {
  struct Triangle {
    std::array<Vec2, 3> uv;
    uint32_t mask;
  };
  std::vector<AlphaMask> masks;
  std::vector<Triangle> triangles;
};

/// Records for every triangle of the hierarchy, same indices. A triangle whose object casts no
/// shadows (design §8) gets the all-zero record, which no segment hits: every backend asks this
/// one test, so all of them see through it alike. With `cutouts`, a triangle of a cut-out Pure
/// with texture coordinates gets an entry there, which its record names.
inline std::vector<TriangleRecord> make_triangle_records(const Hierarchy& h,
                                                         Cutouts* cutouts = nullptr) {
  const Triangles& triangles = h.triangles;
  std::vector<TriangleRecord> out(triangles.size());
  std::vector<int64_t> mask_of(h.objects.size(), -1);
  for (size_t i = 0; i < triangles.size(); ++i) {
    const size_t object = size_t(triangles.object[i]);
    const SceneObject& o = h.objects[object];
    if (!o.casts_shadows) continue;
    out[i] = make_triangle_record(triangles.corners[i]);
    if (cutouts && o.cutout && i < triangles.uv.size() && std::isfinite(triangles.uv[i][0].x) &&
        out[i].normal != Vec3(0.0f)) {
      if (mask_of[object] < 0) {
        mask_of[object] = int64_t(cutouts->masks.size());
        cutouts->masks.push_back(o.cutout);
      }
      cutouts->triangles.push_back({triangles.uv[i], uint32_t(mask_of[object])});
      out[i].cutout = uint32_t(cutouts->triangles.size());
    }
  }
  return out;
}

/// Eight triangle records side by side (structure of arrays, the fields named as in
/// TriangleRecord), lane i of every field from one record; unused lanes hold the all-zero record,
/// which nothing hits.
struct alignas(32) TrianglePacket {
  static constexpr uint32_t kLanes = 8;
  using Lanes = float __attribute__((vector_size(kLanes * sizeof(float))));
  struct LanesVec3 {
    Lanes x{}, y{}, z{};
  };
  LanesVec3 normal;
  Lanes plane_offset{};
  LanesVec3 s_a, s_b, c;

  void set(uint32_t lane, const TriangleRecord& r) {
    const auto put = [lane](LanesVec3& to, const Vec3& v) {
      to.x[lane] = v.x, to.y[lane] = v.y, to.z[lane] = v.z;
    };
    put(normal, r.normal), put(s_a, r.s_a), put(s_b, r.s_b), put(c, r.c);
    plane_offset[lane] = r.plane_offset;
  }
};

/// The design §6 test of one segment against R = TriangleRecord (returns bool) or TrianglePacket
/// (returns the mask of lanes hit). One expression for both, evaluated in the same order, so a
/// lane of the packet test answers exactly what the one-triangle test does: the visibility
/// library is compiled without floating-point contraction (-ffp-contract=off), which would
/// otherwise fuse products into FMAs differently in the two forms. One triangle returns as soon
/// as the segment misses its plane (most triangles of a cell lie off the segment's span); the
/// packet makes every comparison and ands the results, so its only branch is the caller's on the
/// mask. A segment parallel to the plane needs no test of its own: n·direction = 0 makes
/// t = ±inf or NaN, which fails 0 < t < 1.
template <class R>
[[gnu::always_inline]] inline auto barycentric_hit(const R& r, const Vec3& o, const Vec3& d) {
  const auto denom = r.normal.x * d.x + r.normal.y * d.y + r.normal.z * d.z;
  const auto num = r.plane_offset - (r.normal.x * o.x + r.normal.y * o.y + r.normal.z * o.z);
  const auto t = num / denom;
  const auto qx = o.x + t * d.x - r.c.x, qy = o.y + t * d.y - r.c.y, qz = o.z + t * d.z - r.c.z;
  if constexpr (!std::is_same_v<R, TrianglePacket>) {
    if (!(t > 0.0f && t < 1.0f)) return false;
  }
  const auto alpha = qx * r.s_a.x + qy * r.s_a.y + qz * r.s_a.z;
  const auto beta = qx * r.s_b.x + qy * r.s_b.y + qz * r.s_b.z;
  const auto hit =
      (t > 0.0f) & (t < 1.0f) & (alpha >= 0.0f) & (beta >= 0.0f) & (alpha + beta <= 1.0f);
  if constexpr (std::is_same_v<R, TrianglePacket>) {
    uint32_t mask = 0;
    for (uint32_t lane = 0; lane < TrianglePacket::kLanes; ++lane) {
      mask |= uint32_t(hit[lane] != 0) << lane;
    }
    return mask;
  } else {
    return hit != 0;
  }
}

/// Ray–triangle intersection by barycentric coordinates (design §6; the plane/barycentric form of
/// Snyder & Barr, "Ray Tracing Complex Models Containing Surface Tessellations", SIGGRAPH 1987):
/// true if origin + t·direction meets the triangle for some t in the open interval (0, 1), with
/// the point inside or on the edges (α ≥ 0, β ≥ 0, α + β ≤ 1). A segment parallel to the plane
/// (n·direction = 0, including lying in it) never hits. Pure function, float arithmetic.
inline bool segment_hits_triangle(const TriangleRecord& r, const Vec3& origin,
                                  const Vec3& direction) {
  return barycentric_hit(r, origin, direction);
}

/// Where the segment meets the triangle: the t in (0, 1) of segment_hits_triangle's test when it
/// hits (the same expressions in the same order: hit exactly when that test hits), else +inf.
inline float segment_hit_distance(const TriangleRecord& r, const Vec3& o, const Vec3& d) {
  const float denom = r.normal.x * d.x + r.normal.y * d.y + r.normal.z * d.z;
  const float num = r.plane_offset - (r.normal.x * o.x + r.normal.y * o.y + r.normal.z * o.z);
  const float t = num / denom;
  const float qx = o.x + t * d.x - r.c.x, qy = o.y + t * d.y - r.c.y, qz = o.z + t * d.z - r.c.z;
  if (!(t > 0.0f && t < 1.0f)) return std::numeric_limits<float>::infinity();
  const float alpha = qx * r.s_a.x + qy * r.s_a.y + qz * r.s_a.z;
  const float beta = qx * r.s_b.x + qy * r.s_b.y + qz * r.s_b.z;
  const bool hit = (alpha >= 0.0f) & (beta >= 0.0f) & (alpha + beta <= 1.0f);
  return hit ? t : std::numeric_limits<float>::infinity();
}

/// Where the segment meets cut-out triangle r (which segment_hits_triangle says it meets), is
/// the mask opaque? Barycentrics by the same expressions as that test: α weights corner a, β
/// corner b.
inline bool cutout_opaque(const TriangleRecord& r, const Cutouts& cutouts, const Vec3& o,
                          const Vec3& d) {
  const Cutouts::Triangle& c = cutouts.triangles[r.cutout - 1];
  const float denom = r.normal.x * d.x + r.normal.y * d.y + r.normal.z * d.z;
  const float num = r.plane_offset - (r.normal.x * o.x + r.normal.y * o.y + r.normal.z * o.z);
  const float t = num / denom;
  const float qx = o.x + t * d.x - r.c.x, qy = o.y + t * d.y - r.c.y, qz = o.z + t * d.z - r.c.z;
  const float alpha = qx * r.s_a.x + qy * r.s_a.y + qz * r.s_a.z;
  const float beta = qx * r.s_b.x + qy * r.s_b.y + qz * r.s_b.z;
  const Vec2 uv = c.uv[0] * alpha + c.uv[1] * beta + c.uv[2] * (1.0f - alpha - beta);
  return opaque_at(cutouts.masks[c.mask], uv);
}

/// The shadow test every backend makes: the segment meets the triangle, and where a cut-out
/// triangle is met its mask is opaque.
inline bool segment_blocked(const TriangleRecord& r, const Cutouts& cutouts, const Vec3& origin,
                            const Vec3& direction) {
  return segment_hits_triangle(r, origin, direction) &&
         (r.cutout == 0 || cutout_opaque(r, cutouts, origin, direction));
}

/// segment_hit_distance for first_hit, through a cut-out's holes alike: +inf where it passes.
inline float segment_block_distance(const TriangleRecord& r, const Cutouts& cutouts,
                                    const Vec3& origin, const Vec3& direction) {
  const float t = segment_hit_distance(r, origin, direction);
  if (r.cutout == 0 || t == std::numeric_limits<float>::infinity()) return t;
  return cutout_opaque(r, cutouts, origin, direction) ? t : std::numeric_limits<float>::infinity();
}

/// Keeps the nearer of two hits (the lower triangle index at the same t); t = +inf: a miss.
inline void keep_nearer(SegmentHitRecord& best, float t, uint32_t triangle) {
  if (t == std::numeric_limits<float>::infinity()) return;
  if (t < best.t || (t == best.t && triangle < best.triangle)) best = {t, triangle};
}

/// The public answer for the nearest hit found among `records`.
inline SegmentHit hit_of(const SegmentHitRecord& best, const std::vector<TriangleRecord>& records) {
  if (best.triangle == ~0u) return {};
  return {true, best.t, records[best.triangle].normal};
}

/// segment_hits_triangle on a packet's eight lanes at once: bit i set when lane i is hit.
inline uint32_t segment_hits_packet(const TrianglePacket& p, const Vec3& origin,
                                    const Vec3& direction) {
  return barycentric_hit(p, origin, direction);
}

}  // namespace rad
