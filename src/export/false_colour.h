// The light arriving shown in false colour, after the convention of Radiance's falsecolor: each
// pixel's illuminance mapped onto a colour scale from dark blue through green and yellow to red,
// linear or logarithmic, with a legend of labelled steps and the unit on the image's left side.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "export/camera.h"
#include "export/image.h"
#include "export/image_render.h"

namespace rad {

/// What the user asks of the scale.
struct FalseColourOptions {
  double max = 0.0;     // the top of the scale (lux); 0: a round number above most values
  int log_decades = 0;  // 0: linear from 0; N: logarithmic over the N decades below max
};

/// The scale an image is drawn with.
struct FalseColourScale {
  double max = 1.0;
  int log_decades = 0;
  std::vector<double> ticks;  // the values labelled in the legend, increasing
};

/// The most decades a logarithmic scale may span.
inline constexpr int kMaxFalseColourDecades = 12;

/// The luminance of an RGB illuminance with the Rec. 709 (sRGB) weights 0.2126, 0.7152, 0.0722:
/// what a lux meter reads when the RGB channels are the scene's linear primaries.
float luminance_of(const Vec3& rgb);

/// The smallest round number (1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten) at or above
/// the 99th percentile of the positive values; 1 when none is positive.
double round_scale_max(std::span<const float> values);

/// The scale for `values`: o.max, or round_scale_max(values) when it is 0; ticks at round steps
/// (4 to 10 steps of 1, 2, 2.5 or 5 times a power of ten when the maximum allows, else 8 equal
/// steps, Radiance's default) from 0, or for a logarithmic scale at each decade (and at 2 and 5
/// times each when it spans at most 2 decades). Throws rad::Error for a negative or non-finite
/// max or decades outside 0 to kMaxFalseColourDecades.
FalseColourScale make_false_colour_scale(std::span<const float> values,
                                         const FalseColourOptions& o);

/// Where `value` lies on the scale, 0 at its bottom to 1 at its top, clamped (Radiance's
/// mapping: value / max, or log10(value / max) / decades + 1).
float scale_position(const FalseColourScale& scale, double value);

/// The palette at position v in [0, 1] (clamped) as a display colour (sRGB-encoded, 0 to 1):
/// dark blue, blue, cyan, green, yellow, orange, red.
Vec3 false_colour_display(float v);

/// A legend label: at most 4 significant digits, no trailing zeros, thousands as k and millions
/// as M from 10,000 on ("0", "0.25", "62.5", "1000", "12.5k", "2M"), tiny values as "1e-07".
std::string format_scale_value(double value);

/// Where the legend lies in an image `height` pixels high, left of the rendered view.
struct LegendLayout {
  int width = 0;  // the strip's width (0: too low an image for a legend)
  int font_scale = 1;
  int bar_left = 0, bar_right = 0;  // the colour bar's columns [left, right)
  int bar_top = 0, bar_bottom = 0;  // the rows of the scale's top (1) and bottom (0), inclusive
};
LegendLayout legend_layout(const FalseColourScale& scale, std::string_view unit, int height);

/// The legend's row for scale position v in [0, 1]: bar_bottom at 0, bar_top at 1.
int legend_row(const LegendLayout& layout, float v);

/// The scene rendered in false colour: per-vertex `values` (one per position) interpolated over
/// each face as render_image interpolates colours, each pixel's mean value over the subsamples
/// a front face covers mapped through the palette (blended with the black background by that
/// coverage), and the legend (labelled ticks and `unit`) in a strip added to the left, so the
/// image is legend_layout(...).width + options.width pixels wide. Pixels are linear: written as
/// PNG with scale 1 and no curve they hold the palette's bytes.
Image render_false_colour(std::span<const Vec3> positions, std::span<const float> values,
                          std::span<const uint32_t> indices, const Camera& camera,
                          const RenderOptions& options, const FalseColourScale& scale,
                          std::string_view unit);

}  // namespace rad
