// Precomputed triangle records and the segment–triangle test of SPEC §6 (barycentrics via s_a,
// s_b).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// One triangle a, b, c prepared for the SPEC §6 test, 64 bytes (one cache line):
/// e_a = a − c, e_b = b − c, n = e_a × e_b, plane n·p = plane_offset,
/// s_a = e_b × n / |n|², s_b = n × e_a / |n|² (= e_a × (e_b × e_a) / |n|²), so that any p on the
/// plane is c + α e_a + β e_b with α = (p − c)·s_a, β = (p − c)·s_b. A degenerate triangle
/// (n = 0) gets all-zero vectors and is never hit.
struct alignas(16) TriangleRecord {
  Vec3 normal{0.0f};  // n = e_a × e_b, unnormalised
  float plane_offset = 0.0f;
  Vec3 s_a{0.0f};
  float pad0 = 0.0f;
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

/// Records for every triangle of the hierarchy, same indices. A triangle whose object casts no
/// shadows (SPEC §8) gets the all-zero record, which no segment hits: every backend asks this
/// one test, so all of them see through it alike.
inline std::vector<TriangleRecord> make_triangle_records(const Hierarchy& h) {
  const Triangles& triangles = h.triangles;
  std::vector<TriangleRecord> out(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    if (h.objects[size_t(triangles.object[i])].casts_shadows) {
      out[i] = make_triangle_record(triangles.corners[i]);
    }
  }
  return out;
}

/// Ray–triangle intersection by barycentric coordinates (SPEC §6; the plane/barycentric form of
/// Snyder & Barr, "Ray Tracing Complex Models Containing Surface Tessellations", SIGGRAPH 1987):
/// true if origin + t·direction meets the triangle for some t in the open interval (0, 1), with
/// the point inside or on the edges (α ≥ 0, β ≥ 0, α + β ≤ 1). A segment parallel to the plane
/// (n·direction = 0, including lying in it) never hits. Pure function, float arithmetic.
inline bool segment_hits_triangle(const TriangleRecord& r, const Vec3& origin,
                                  const Vec3& direction) {
  float denom = glm::dot(r.normal, direction);
  float num = r.plane_offset - glm::dot(r.normal, origin);
  if (!(denom != 0.0f)) return false;
  float t = num / denom;
  if (!(t > 0.0f && t < 1.0f)) return false;
  Vec3 q = origin + t * direction - r.c;
  float alpha = glm::dot(q, r.s_a);
  float beta = glm::dot(q, r.s_b);
  return alpha >= 0.0f && beta >= 0.0f && alpha + beta <= 1.0f;
}

}  // namespace rad
