#include "solver/form_factor.h"

#include <cmath>

namespace rad {

float point_to_triangle_form_factor(const Vec3& x, const Vec3& n, const Vec3& a, const Vec3& b,
                                    const Vec3& c) {
  // Sutherland-Hodgman against the plane (p - x) . n >= 0: a triangle gives at most 4 points.
  const Vec3 in[3] = {a - x, b - x, c - x};
  float h[3];
  for (int i = 0; i < 3; ++i) h[i] = glm::dot(in[i], n);
  if (h[0] <= 0.0f && h[1] <= 0.0f && h[2] <= 0.0f) return 0.0f;
  Vec3 r[4];
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (h[i] >= 0.0f) r[m++] = in[i];
    if ((h[i] > 0.0f && h[j] < 0.0f) || (h[i] < 0.0f && h[j] > 0.0f)) {
      const float t = h[i] / (h[i] - h[j]);
      r[m++] = in[i] + (in[j] - in[i]) * t;
    }
  }
  if (m < 3) return 0.0f;
  // Contour integral in double: edge terms nearly cancel for distant sources.
  double sum = 0.0;
  for (int i = 0; i < m; ++i) {
    const glm::dvec3 p(r[i]), q(r[(i + 1) % m]);
    const glm::dvec3 cr = glm::cross(p, q);
    const double len = glm::length(cr);
    if (len <= 0.0) continue;
    const double angle = std::atan2(len, glm::dot(p, q));
    sum += angle * glm::dot(glm::dvec3(n), cr) / len;
  }
  return float(std::min(1.0, std::abs(sum) / (2.0 * std::numbers::pi)));
}

}  // namespace rad
