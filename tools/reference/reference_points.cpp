#include "reference/reference_points.h"

#include <cmath>

#include "reference/rng.h"

namespace rad {

std::vector<uint32_t> points_per_triangle(const Triangles& t, const PointOptions& o) {
  double total_area = 0.0;
  for (float a : t.area) total_area += a;
  std::vector<uint32_t> n(t.size(), o.min_per_triangle);
  if (total_area <= 0.0) return n;
  // Systematic sampling of the cumulative area: point k sits at (k + 1/2) x area / total, and a
  // triangle gets the points that fall on its stretch. Exactly `total` points, within one of
  // each triangle's share; rounding each share on its own would give a finely tessellated
  // surface (every share below 1/2) no points at all.
  const double per_point = total_area / double(o.total);
  double before = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double after = before + t.area[i];
    const uint32_t share =
        uint32_t(std::floor(after / per_point + 0.5) - std::floor(before / per_point + 0.5));
    n[i] = std::max(o.min_per_triangle, share);
    before = after;
  }
  return n;
}

ReferencePoint point_on_triangle(const Triangles& t, int32_t triangle, float u, float v) {
  const auto& c = t.corners[size_t(triangle)];
  const DVec3 a(c[0]), b(c[1]), cc(c[2]);
  ReferencePoint p;
  p.triangle = triangle;
  p.u = u;
  p.v = v;
  p.position = Vec3(a + double(u) * (b - a) + double(v) * (cc - a));
  p.normal = t.normal[size_t(triangle)];
  return p;
}

std::vector<ReferencePoint> make_reference_points(const Triangles& t, const PointOptions& o) {
  if (o.corners) {
    std::vector<ReferencePoint> points;
    const float far = 1.0f - 2.0f * o.inset;
    for (size_t tri = 0; tri < t.size(); ++tri) {
      points.push_back(point_on_triangle(t, int32_t(tri), o.inset, o.inset));
      points.push_back(point_on_triangle(t, int32_t(tri), far, o.inset));
      points.push_back(point_on_triangle(t, int32_t(tri), o.inset, far));
    }
    return points;
  }
  const std::vector<uint32_t> counts = points_per_triangle(t, o);
  const double inv_phi = 0.6180339887498949;
  const double keep = 1.0 - 3.0 * double(o.inset);
  std::vector<ReferencePoint> points;
  for (size_t tri = 0; tri < t.size(); ++tri) {
    Pcg32 rng(o.seed, tri);
    const double shift = rng.uniform();
    const uint32_t n = counts[tri];
    for (uint32_t i = 0; i < n; ++i) {
      const double r1 = (i + rng.uniform()) / n;
      const double r2 = std::fmod(shift + i * inv_phi, 1.0);
      const double s = std::sqrt(r1);
      const double u = o.inset + keep * s * (1.0 - r2);
      const double v = o.inset + keep * s * r2;
      points.push_back(point_on_triangle(t, int32_t(tri), float(u), float(v)));
    }
  }
  return points;
}

}  // namespace rad
