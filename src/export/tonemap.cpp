#include "export/tonemap.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace rad {

ToneCurve parse_tone_curve(std::string_view name) {
  if (name == "clamp") return ToneCurve::Clamp;
  if (name == "reinhard") return ToneCurve::Reinhard;
  if (name == "aces") return ToneCurve::Aces;
  throw Error("unknown tone curve '" + std::string(name) + "' (expected clamp, reinhard or aces)");
}

const char* to_string(ToneCurve curve) {
  switch (curve) {
    case ToneCurve::Clamp:
      return "clamp";
    case ToneCurve::Reinhard:
      return "reinhard";
    case ToneCurve::Aces:
      return "aces";
  }
  return "clamp";
}

float auto_exposure(std::span<const Vec3> values, float ignore_above, float stops) {
  std::vector<float> v;
  v.reserve(values.size());
  for (const Vec3& c : values) {
    const float m = max_component(c);
    if (m > 0.0f && m <= ignore_above) v.push_back(m);
  }
  float ref = 1.0f;
  if (!v.empty()) {
    const size_t k = std::min(v.size() - 1, size_t(double(v.size()) * 0.99));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    ref = v[k];
  }
  return std::exp2(stops) / (ref > 0.0f ? ref : 1.0f);
}

Vec3 tone_map(const Vec3& linear, const ToneMap& tm) {
  const Vec3 x = glm::max(linear * tm.scale, Vec3(0.0f));
  switch (tm.curve) {
    case ToneCurve::Clamp:
      return glm::min(x, Vec3(1.0f));
    case ToneCurve::Reinhard:
      return x / (Vec3(1.0f) + x);
    case ToneCurve::Aces: {
      // Narkowicz 2015 fit of the ACES filmic curve.
      const Vec3 y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
      return glm::clamp(y, Vec3(0.0f), Vec3(1.0f));
    }
  }
  return x;
}

float srgb_encode(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

void to_srgb8(const Vec3& linear, const ToneMap& tm, uint8_t rgb[3]) {
  const Vec3 d = tone_map(linear, tm);
  for (int k = 0; k < 3; ++k) rgb[k] = uint8_t(std::lround(srgb_encode(d[k]) * 255.0f));
}

}  // namespace rad
