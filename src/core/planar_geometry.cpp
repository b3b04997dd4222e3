#include "core/planar_geometry.h"

#include <cmath>

namespace rad {

double convex_polygon_area(const DVec2* a, size_t n) {
  double twice = 0.0;
  for (size_t i = 1; i + 1 < n; ++i) {
    twice += (a[i].x - a[0].x) * (a[i + 1].y - a[0].y) - (a[i + 1].x - a[0].x) * (a[i].y - a[0].y);
  }
  return 0.5 * std::abs(twice);
}

double triangle_area_inside(const std::array<DVec2, 3>& t, const DVec2* c, size_t m) {
  DVec2 a[16], b[16];
  size_t n = 3;
  for (size_t i = 0; i < 3; ++i) a[i] = t[i];
  const double orient =
      (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[2].x - c[0].x) * (c[1].y - c[0].y);
  const double s = orient >= 0.0 ? 1.0 : -1.0;
  for (size_t e = 0; e < m && n > 0; ++e) {
    const DVec2 &p0 = c[e], &p1 = c[(e + 1) % m];
    auto inside = [&](const DVec2& p) {
      return s * ((p1.x - p0.x) * (p.y - p0.y) - (p1.y - p0.y) * (p.x - p0.x));
    };
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
      const DVec2 &p = a[i], &q = a[(i + 1) % n];
      const double dp = inside(p), dq = inside(q);
      if (dp >= 0.0) b[k++] = p;
      if ((dp >= 0.0) != (dq >= 0.0)) b[k++] = p + (q - p) * (dp / (dp - dq));
    }
    n = k;
    for (size_t i = 0; i < n; ++i) a[i] = b[i];
  }
  return convex_polygon_area(a, n);
}

double triangle_area_in_rect(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi) {
  const DVec2 rect[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  return triangle_area_inside(t, rect, 4);
}

bool triangle_holds_rect(const std::array<DVec2, 3>& t, const DVec2& lo, const DVec2& hi) {
  const double orient =
      (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
  const DVec2 q[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (size_t e = 0; e < 3; ++e) {
    const DVec2 &a = t[e], &b = t[(e + 1) % 3];
    for (const DVec2& p : q) {
      if (orient * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) < 0.0) return false;
    }
  }
  return orient != 0.0;
}

std::array<DVec2, 3> flatten_triangle(const DVec3& origin, const DVec3& u, const DVec3& w,
                                      const std::array<Vec3, 3>& c) {
  std::array<DVec2, 3> t;
  for (size_t k = 0; k < 3; ++k) {
    const DVec3 d = DVec3(c[k]) - origin;
    t[k] = {glm::dot(d, u), glm::dot(d, w)};
  }
  return t;
}

std::array<DVec2, 2> bounds_2d(const std::array<DVec2, 3>& t) {
  return {glm::min(glm::min(t[0], t[1]), t[2]), glm::max(glm::max(t[0], t[1]), t[2])};
}

void plane_frame(const DVec3& n, DVec3& u, DVec3& w) {
  const DVec3 a = std::abs(n.x) < 0.6 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
  u = glm::normalize(glm::cross(n, a));
  w = glm::cross(n, u);
}

}  // namespace rad
