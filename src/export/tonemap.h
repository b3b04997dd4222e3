// From linear radiosity to display colours: exposure, tone curve, sRGB encoding.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "core/math.h"

namespace rad {

enum class ToneCurve : uint8_t { Clamp, Reinhard, Aces };
/// "clamp" | "reinhard" | "aces"; throws rad::Error otherwise.
ToneCurve parse_tone_curve(std::string_view name);
/// The name parse_tone_curve takes.
const char* to_string(ToneCurve curve);

struct ToneMap {
  float scale = 1.0f;  // linear multiplier applied before the curve
  ToneCurve curve = ToneCurve::Clamp;
};

/// Automatic exposure: the scale that maps the 99th percentile of the values' largest channel
/// (ignoring values above `ignore_above`, e.g. light sources) to 1, times 2^stops.
float auto_exposure(std::span<const Vec3> values, float ignore_above, float stops);

/// Linear colour -> display-referred colour in [0, 1] (before sRGB encoding).
Vec3 tone_map(const Vec3& linear, const ToneMap& tm);

/// sRGB transfer function of one channel in [0, 1].
float srgb_encode(float linear);

/// tone_map then sRGB, as bytes.
void to_srgb8(const Vec3& linear, const ToneMap& tm, uint8_t rgb[3]);

}  // namespace rad
