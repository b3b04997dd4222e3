#include "solver/form_factor.h"

#include <cmath>

namespace rad {

namespace {

// The contour sum over the polygon r[0..m) (points relative to the receiver) whose edges are
// e[i] = r[i+1] - r[i], in T. Each cross product is taken with the edge (p x q = p x (q - p)):
// p and q are nearly parallel for a distant source, and p x q from the rounded points would
// lose digits that the edge, computed from the corners themselves, keeps.
template <typename T>
T contour_sum(const Vec3* r, const Vec3* e, int m, const Vec3& n) {
  using V = glm::vec<3, T>;
  const V nn(n);
  T sum = 0;
  for (int i = 0; i < m; ++i) {
    const V p(r[i]), q(r[(i + 1) % m]);
    const V cr = glm::cross(p, V(e[i]));
    const T len = glm::length(cr);
    if (len <= T(0)) continue;
    const T angle = std::atan2(len, glm::dot(p, q));
    sum += angle * glm::dot(nn, cr) / len;
  }
  return sum;
}

template <typename T>
T outline_sum(const Vec3& x, const Vec3& n, const Vec3* a, const Vec3* b, size_t count,
              const Vec3& axis) {
  using V = glm::vec<3, T>;
  const V nn(n), xx(x);
  // Polar angle frame in the tangent plane: f points from x to the line where it meets the
  // surface's plane, g = n x f.
  V f = glm::cross(glm::cross(nn, V(axis)), nn);
  const T fl = glm::length(f);
  V g(0);
  const bool frame = fl > T(1e-6);
  if (frame) {
    f /= fl;
    if (glm::dot(f, V(axis)) > T(0)) f = -f;  // x is above the surface: towards it is down
    g = glm::cross(nn, f);
  }
  auto polar = [&](const V& r) { return std::atan2(glm::dot(r, g), glm::dot(r, f)); };
  T sum = 0, closing = 0;
  for (size_t i = 0; i < count; ++i) {
    V p = V(a[i]) - xx, q = V(b[i]) - xx;
    const T hp = glm::dot(p, nn), hq = glm::dot(q, nn);
    if (hp <= T(0) && hq <= T(0)) continue;
    V e = V(b[i]) - V(a[i]);
    if (hq <= T(0)) {  // leaves the front half-space
      q = p + (q - p) * (hp / (hp - hq));
      e = q - p;
      if (frame) closing -= polar(q);
    } else if (hp <= T(0)) {  // enters it
      p = p + (q - p) * (hp / (hp - hq));
      e = q - p;
      if (frame) closing += polar(p);
    }
    const V cr = glm::cross(p, e);
    const T len = glm::length(cr);
    if (len <= T(0)) continue;
    sum += std::atan2(len, glm::dot(p, q)) * glm::dot(nn, cr) / len;
  }
  return sum + closing;
}

}  // namespace

float point_to_outline_form_factor(const Vec3& x, const Vec3& n, const Vec3* a, const Vec3* b,
                                   size_t count, const Vec3& axis, Arithmetic arithmetic) {
  const double sum = arithmetic == Arithmetic::Single
                         ? double(outline_sum<float>(x, n, a, b, count, axis))
                         : outline_sum<double>(x, n, a, b, count, axis);
  return float(std::min(1.0, std::abs(sum) / (2.0 * std::numbers::pi)));
}

float point_to_triangle_form_factor(const Vec3& x, const Vec3& n, const Vec3& a, const Vec3& b,
                                    const Vec3& c, Arithmetic arithmetic) {
  // Sutherland-Hodgman against the plane (p - x) . n >= 0: a triangle gives at most 4 points.
  const Vec3 in[3] = {a - x, b - x, c - x};
  float h[3];
  for (int i = 0; i < 3; ++i) h[i] = glm::dot(in[i], n);
  if (h[0] <= 0.0f && h[1] <= 0.0f && h[2] <= 0.0f) return 0.0f;
  Vec3 r[4], e[4];
  int m = 0;
  if (h[0] >= 0.0f && h[1] >= 0.0f && h[2] >= 0.0f) {  // wholly in front: edges from the corners
    for (int i = 0; i < 3; ++i) r[i] = in[i];
    e[0] = b - a, e[1] = c - b, e[2] = a - c;
    m = 3;
  } else {
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (h[i] >= 0.0f) r[m++] = in[i];
      if ((h[i] > 0.0f && h[j] < 0.0f) || (h[i] < 0.0f && h[j] > 0.0f)) {
        const float t = h[i] / (h[i] - h[j]);
        r[m++] = in[i] + (in[j] - in[i]) * t;
      }
    }
    if (m < 3) return 0.0f;
    for (int i = 0; i < m; ++i) e[i] = r[(i + 1) % m] - r[i];
  }
  const double sum = arithmetic == Arithmetic::Single ? double(contour_sum<float>(r, e, m, n))
                                                      : contour_sum<double>(r, e, m, n);
  return float(std::min(1.0, std::abs(sum) / (2.0 * std::numbers::pi)));
}

}  // namespace rad
