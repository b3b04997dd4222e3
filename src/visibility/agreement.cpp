#include "visibility/agreement.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/planar_geometry.h"
#include "visibility/segment.h"

namespace rad {

namespace {

// Closest distance between segments p1q1 and p2q2 (Ericson, "Real-Time Collision Detection",
// 2005, §5.1.9), in double.
double segment_segment_distance(DVec3 p1, DVec3 q1, DVec3 p2, DVec3 q2) {
  DVec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  double s = 0.0, t = 0.0;
  if (a <= 0.0 && e <= 0.0) return glm::length(r);
  if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    double c = glm::dot(d1, r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      double b = glm::dot(d1, d2), denom = a * e - b * b;
      s = denom != 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return glm::length((p1 + d1 * s) - (p2 + d2 * t));
}

// Closest distance from p to triangle abc (Ericson 2005, §5.1.5), in double.
double point_triangle_distance(DVec3 p, DVec3 a, DVec3 b, DVec3 c) {
  DVec3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  DVec3 bp = p - b;
  double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  DVec3 cp = p - c;
  double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  double denom = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

std::vector<uint8_t> answers(const VisibilityBackend& b, const std::vector<Segment>& s) {
  std::vector<uint8_t> out(s.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, s.size(), 256),
                    [&](const tbb::blocked_range<size_t>& r) {
                      VisibilityStats stats;
                      b.occluded(std::span(s).subspan(r.begin(), r.size()),
                                 std::span(out).subspan(r.begin(), r.size()), stats);
                    });
  return out;
}

}  // namespace

double ambiguity_distance(const Hierarchy& h, const Segment& s) {
  DVec3 p(s.origin), q(DVec3(s.origin) + DVec3(s.direction));
  double best = INFINITY;
  for (const auto& t : h.triangles.corners) {
    DVec3 a(t[0]), b(t[1]), c(t[2]);
    best = std::min({best, point_triangle_distance(p, a, b, c), point_triangle_distance(q, a, b, c),
                     segment_segment_distance(p, q, a, b), segment_segment_distance(p, q, b, c),
                     segment_segment_distance(p, q, c, a)});
  }
  return best;
}

std::vector<Segment> random_segments(const Hierarchy& h, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto& tris = h.triangles;
  std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
  float offset = shadow_offset(h.bounds);
  Vec3 lo = h.bounds.lo - 0.1f * h.bounds.extent(), e = 1.2f * h.bounds.extent();
  auto surface_point = [&](size_t i) {
    const float a = u(rng);
    const glm::vec2 w = fold_into_triangle(a, u(rng));
    const auto& t = tris.corners[i];
    return t[2] + w.x * (t[0] - t[2]) + w.y * (t[1] - t[2]);
  };
  std::vector<Segment> out(n);
  for (size_t k = 0; k < n; ++k) {
    size_t i = pick(rng);
    Vec3 from = surface_point(i), to;
    Vec3 to_normal(0.0f);
    switch (k % 3) {
      case 0: {  // surface to surface, as the solver casts them
        size_t j = pick(rng);
        to = surface_point(j);
        to_normal = tris.normal[j];
        break;
      }
      case 1:  // anywhere to anywhere
        from = lo + e * Vec3(u(rng), u(rng), u(rng));
        to = lo + e * Vec3(u(rng), u(rng), u(rng));
        break;
      default: {  // to somewhere near a random triangle: dense spots, edges and corners
        const auto& t = tris.corners[pick(rng)];
        float r = 2.0f * std::sqrt(glm::length(glm::cross(t[1] - t[0], t[2] - t[0])));
        to = (t[0] + t[1] + t[2]) / 3.0f + r * Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
      }
    }
    Vec3 from_normal = k % 3 == 1 ? Vec3(0.0f) : tris.normal[i];
    if (glm::dot(from_normal, to - from) < 0.0f) from_normal = -from_normal;
    if (glm::dot(to_normal, from - to) < 0.0f) to_normal = -to_normal;
    out[k] = make_shadow_segment(from, from_normal, to, to_normal, offset);
  }
  return out;
}

double ambiguity_limit(const Hierarchy& h) { return 1e-6 * h.bounds.magnitude(); }

RayAgreement compare_rays(const Hierarchy& h, const VisibilityBackend& oracle,
                          const VisibilityBackend& backend, std::span<const Segment> segments) {
  const std::vector<Segment> s(segments.begin(), segments.end());
  const std::vector<uint8_t> expected = answers(oracle, s), got = answers(backend, s);
  RayAgreement a;
  a.segments = s.size();
  a.blocked = size_t(std::count(expected.begin(), expected.end(), uint8_t{1}));
  const double limit = ambiguity_limit(h);
  for (size_t k = 0; k < s.size(); ++k) {
    if (got[k] == expected[k]) continue;
    const double d = ambiguity_distance(h, s[k]);
    if (d < limit) {
      ++a.near;
      a.worst_near = std::max(a.worst_near, d);
    } else {
      ++a.far;
      a.worst_far = std::max(a.worst_far, d);
    }
    a.mismatches.push_back({s[k], expected[k], got[k], d});
  }
  return a;
}

}  // namespace rad
