#include "scene/photometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {

const char* to_string(CSymmetry s) {
  switch (s) {
    case CSymmetry::Rotational:
      return "rotationally symmetric";
    case CSymmetry::Quadrant:
      return "quadrant symmetric (C 0-90)";
    case CSymmetry::Bilateral:
      return "bilaterally symmetric (C 0-180)";
    case CSymmetry::Bilateral90:
      return "bilaterally symmetric (C 90-270)";
    case CSymmetry::Full:
      return "full (C 0-360)";
  }
  return "?";
}

namespace {

// The cell of increasing `a` holding x (clamped to the ends) and the fraction across it.
void locate(const std::vector<float>& a, float x, size_t& i, float& t) {
  if (a.size() < 2) {
    i = 0, t = 0.0f;
    return;
  }
  const auto it = std::upper_bound(a.begin(), a.end(), x);
  const size_t k = size_t(std::max<std::ptrdiff_t>(it - a.begin(), 1));
  i = std::min(k - 1, a.size() - 2);
  t = std::clamp((x - a[i]) / (a[i + 1] - a[i]), 0.0f, 1.0f);
}

}  // namespace

float Photometry::candela_at(float gamma, float c) const {
  const size_t nv = vertical.size(), nh = horizontal.size();
  if (nv == 0 || nh == 0 || candela.size() != nv * nh) return 0.0f;
  if (!(gamma >= vertical.front() && gamma <= vertical.back())) return 0.0f;  // and NaN
  size_t iv;
  float tv;
  locate(vertical, gamma, iv, tv);
  auto column = [&](size_t h) {
    const float* col = candela.data() + h * nv;
    return nv < 2 ? col[0] : col[iv] + (col[iv + 1] - col[iv]) * tv;
  };
  if (symmetry == CSymmetry::Rotational || nh < 2) return column(0);
  if (!std::isfinite(c)) c = 0.0f;
  c = std::fmod(c, 360.0f);
  if (c < 0.0f) c += 360.0f;
  switch (symmetry) {
    case CSymmetry::Quadrant:
      if (c > 180.0f) c = 360.0f - c;
      if (c > 90.0f) c = 180.0f - c;
      break;
    case CSymmetry::Bilateral:
      if (c > 180.0f) c = 360.0f - c;
      break;
    case CSymmetry::Bilateral90:
      if (c < 90.0f)
        c = 180.0f - c;
      else if (c > 270.0f)
        c = 540.0f - c;
      break;
    case CSymmetry::Rotational:
    case CSymmetry::Full:
      break;
  }
  size_t ih;
  float th;
  locate(horizontal, c, ih, th);
  const float a = column(ih), b = column(ih + 1);
  return a + (b - a) * th;
}

double Photometry::flux() const {
  // The midpoint rule over quarter-degree bands of gamma and one-degree sectors of C: the table
  // is piecewise bilinear in the angles, so this is within a fraction of a percent of exact.
  constexpr int kBands = 720;
  const int sectors = symmetry == CSymmetry::Rotational ? 1 : 360;
  const double deg = std::numbers::pi / 180.0;
  double sum = 0.0;
  for (int i = 0; i < kBands; ++i) {
    const double g0 = 180.0 * i / kBands, g1 = 180.0 * (i + 1) / kBands;
    const double solid = (std::cos(g0 * deg) - std::cos(g1 * deg)) * 2.0 * std::numbers::pi;
    double ring = 0.0;
    for (int s = 0; s < sectors; ++s) {
      ring += candela_at(float(0.5 * (g0 + g1)), float(360.0 * (s + 0.5) / sectors));
    }
    sum += solid * ring / sectors;
  }
  return sum;
}

}  // namespace rad
