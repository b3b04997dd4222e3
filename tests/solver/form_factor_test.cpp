#include "solver/form_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rad {
namespace {

// Differential area to a parallel rectangle a x b at distance c, facing it, with the
// rectangle's corner straight above the point (textbook closed form).
double parallel_corner_rectangle(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * std::numbers::pi);
}

// Midpoint quadrature of cos_r+ |cos_s| / (pi r^2) over the triangle, in double.
double quadrature(Vec3 x, Vec3 n, Vec3 a, Vec3 b, Vec3 c, int m = 400) {
  const glm::dvec3 X(x), N(n), A(a), B(b), C(c);
  const glm::dvec3 ns = glm::normalize(glm::cross(B - A, C - A));
  const double area = 0.5 * glm::length(glm::cross(B - A, C - A)) / (double(m) * m);
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; i + j < m; ++j) {
      auto f = [&](double u, double v) {
        const glm::dvec3 p = A + (B - A) * (u / m) + (C - A) * (v / m);
        const glm::dvec3 d = p - X;
        const double r2 = glm::dot(d, d), r = std::sqrt(r2);
        const double cr = std::max(0.0, glm::dot(N, d) / r), cs = std::abs(glm::dot(ns, d) / r);
        return cr * cs / (std::numbers::pi * r2) * area;
      };
      sum += f(i + 1.0 / 3, j + 1.0 / 3);
      if (i + j + 1 < m) sum += f(i + 2.0 / 3, j + 2.0 / 3);
    }
  }
  return sum;
}

TEST(FormFactor, ParallelSquareAboveMatchesTheClosedForm) {
  // Unit square centred above the point at height h: four corner rectangles of 0.5 x 0.5.
  for (float h : {0.1f, 0.5f, 1.0f, 3.0f}) {
    const Vec3 x(0, 0, 0), n(0, 0, 1);
    const Vec3 p00(-0.5f, -0.5f, h), p10(0.5f, -0.5f, h), p11(0.5f, 0.5f, h), p01(-0.5f, 0.5f, h);
    const double f = double(point_to_triangle_form_factor(x, n, p00, p11, p10)) +
                     point_to_triangle_form_factor(x, n, p00, p01, p11);
    const double exact = 4 * parallel_corner_rectangle(0.5, 0.5, h);
    EXPECT_NEAR(f, exact, 1e-6 + 1e-5 * exact) << "h = " << h;
  }
}

TEST(FormFactor, AgreesWithQuadratureOnRandomTrianglesIncludingClippedOnes) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int clipped = 0;
  for (int t = 0; t < 30; ++t) {
    const Vec3 n = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3 x = Vec3(u(rng), u(rng), u(rng)) * 0.3f + Vec3(0, 0, -1.5f);
    const float h[3] = {glm::dot(a - x, n), glm::dot(b - x, n), glm::dot(c - x, n)};
    clipped += (h[0] > 0) != (h[1] > 0) || (h[1] > 0) != (h[2] > 0);
    const double f = point_to_triangle_form_factor(x, n, a, b, c);
    const double q = quadrature(x, n, a, b, c);
    EXPECT_NEAR(f, q, 2e-4 + 2e-3 * q) << "case " << t;
  }
  EXPECT_GT(clipped, 5) << "the random cases should exercise clipping";
}

TEST(FormFactor, TriangleBehindTheTangentPlaneGivesZero) {
  EXPECT_EQ(point_to_triangle_form_factor({0, 0, 0}, {0, 0, 1}, {0, 0, -1}, {1, 0, -1}, {0, 1, -2}),
            0.0f);
}

// A point at the foot of an infinite-looking perpendicular wall sees it with F -> 1/2 as it
// approaches the wall: the limit the inset of boundary vertices relies on.
TEST(FormFactor, PerpendicularWallSeenFromItsFootTendsToOneHalf) {
  const float L = 1000.0f;
  const Vec3 a(0, -L, 0), b(0, L, 0), c(0, L, L), d(0, -L, L);  // wall x = 0, facing +x
  for (float dist : {1e-1f, 1e-2f, 1e-3f}) {
    const Vec3 x(dist, 0, 0), n(0, 0, 1);
    const float f =
        point_to_triangle_form_factor(x, n, a, c, b) + point_to_triangle_form_factor(x, n, a, d, c);
    EXPECT_NEAR(f, 0.5f, 1e-3f) << dist;
  }
}

TEST(FormFactor, SampleKernelIsZeroBehindEitherSurface) {
  EXPECT_GT(sample_kernel({0, 0, 1}, {0, 0, 1}, {0, 0, -1}, 0.01f), 0.0f);
  EXPECT_EQ(sample_kernel({0, 0, 1}, {0, 0, -1}, {0, 0, -1}, 0.01f), 0.0f);
  EXPECT_EQ(sample_kernel({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, 0.01f), 0.0f);
  // Head-on at distance 1: 1 / (pi + A/n).
  EXPECT_FLOAT_EQ(sample_kernel({0, 0, 1}, {0, 0, 1}, {0, 0, -1}, 0.5f),
                  1.0f / (std::numbers::pi_v<float> + 0.5f));
}

}  // namespace
}  // namespace rad
