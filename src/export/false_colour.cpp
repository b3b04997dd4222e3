#include "export/false_colour.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"
#include "export/bitmap_font.h"

namespace rad {

namespace {

// The palette's stops, display colours: dark enough at 0 that an unlit surface stays apart from
// the black background, green and yellow in the middle where the eye tells steps best, red at
// the top, like falsecolor's scales.
struct Stop {
  float v;
  Vec3 colour;
};
constexpr std::array<Stop, 7> kPalette{{
    {0.00f, {0.00f, 0.00f, 0.30f}},
    {0.15f, {0.00f, 0.15f, 0.85f}},
    {0.32f, {0.00f, 0.65f, 0.85f}},
    {0.48f, {0.10f, 0.80f, 0.20f}},
    {0.66f, {0.95f, 0.95f, 0.00f}},
    {0.82f, {1.00f, 0.55f, 0.00f}},
    {1.00f, {0.90f, 0.00f, 0.00f}},
}};

float srgb_decode(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

Vec3 linear_of(const Vec3& display) {
  return Vec3(srgb_decode(display.x), srgb_decode(display.y), srgb_decode(display.z));
}

// m x 10^k for the steps a reader adds up at a glance.
bool is_round_step(double step) {
  if (!(step > 0.0)) return false;
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (std::abs(mantissa - m) < 1e-6 * m) return true;
  return false;
}

std::string trimmed(std::string s) {
  if (s.find('.') == std::string::npos) return s;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

// At most 4 significant digits, fixed notation.
std::string significant(double v) {
  const int digits = v > 0.0 ? int(std::floor(std::log10(v))) + 1 : 1;
  const int decimals = std::clamp(4 - digits, 0, 7);
  return trimmed(fmt::format("{:.{}f}", v, decimals));
}

}  // namespace

float luminance_of(const Vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

double round_scale_max(std::span<const float> values) {
  std::vector<float> v;
  for (float x : values)
    if (x > 0.0f && std::isfinite(x)) v.push_back(x);
  if (v.empty()) return 1.0;
  const size_t k = std::min(v.size() - 1, size_t(double(v.size()) * 0.99));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  const double p = double(v[k]);
  const double decade = std::pow(10.0, std::floor(std::log10(p)));
  for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0})
    if (m * decade >= p * (1.0 - 1e-9)) return m * decade;
  return 10.0 * decade;
}

FalseColourScale make_false_colour_scale(std::span<const float> values,
                                         const FalseColourOptions& o) {
  if (!(o.max >= 0.0) || !std::isfinite(o.max)) {
    throw Error(
        fmt::format("the false colour scale's maximum must be a positive number (0: "
                    "chosen from the scene), not {}",
                    o.max));
  }
  if (o.log_decades < 0 || o.log_decades > kMaxFalseColourDecades) {
    throw Error(
        fmt::format("a logarithmic false colour scale spans 1 to {} decades (0: linear), "
                    "not {}",
                    kMaxFalseColourDecades, o.log_decades));
  }
  FalseColourScale s;
  s.max = o.max > 0.0 ? o.max : round_scale_max(values);
  s.log_decades = o.log_decades;
  if (s.log_decades == 0) {
    int steps = 8;
    for (int n : {10, 8, 6, 5, 4}) {
      if (is_round_step(s.max / n)) {
        steps = n;
        break;
      }
    }
    for (int i = 0; i <= steps; ++i) s.ticks.push_back(s.max * i / steps);
  } else {
    const double bottom = s.max * std::pow(10.0, -s.log_decades);
    for (int k = s.log_decades; k >= 0; --k) {
      const double decade = s.max * std::pow(10.0, -k);
      s.ticks.push_back(decade);
      if (s.log_decades > 2 || k == 0) continue;
      for (double m : {2.0, 5.0})
        if (m * decade > bottom && m * decade < s.max) s.ticks.push_back(m * decade);
    }
  }
  return s;
}

float scale_position(const FalseColourScale& s, double value) {
  if (!(value > 0.0)) return 0.0f;
  const double x = value / s.max;
  const double v = s.log_decades == 0 ? x : std::log10(x) / s.log_decades + 1.0;
  return float(std::clamp(v, 0.0, 1.0));
}

Vec3 false_colour_display(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  for (size_t i = 1; i < kPalette.size(); ++i) {
    if (v <= kPalette[i].v) {
      const Stop &a = kPalette[i - 1], &b = kPalette[i];
      return glm::mix(a.colour, b.colour, (v - a.v) / (b.v - a.v));
    }
  }
  return kPalette.back().colour;
}

std::string format_scale_value(double v) {
  if (v == 0.0) return "0";
  if (v < 1e-4) return fmt::format("{:.0e}", v);
  if (v >= 1e7) return significant(v / 1e6) + "M";
  if (v >= 1e4) return significant(v / 1e3) + "k";
  return significant(v);
}

LegendLayout legend_layout(const FalseColourScale& scale, std::string_view unit, int height) {
  LegendLayout l;
  l.font_scale = std::clamp((height + 100) / 250, 1, 4);
  const int s = l.font_scale, margin = 3 * s, half_label = (kGlyphHeight * s + 1) / 2;
  l.bar_top = margin + kGlyphHeight * s + margin + half_label;
  l.bar_bottom = height - 1 - margin - half_label;
  if (l.bar_bottom - l.bar_top < 4 * kGlyphHeight) return LegendLayout{};  // no room: none
  l.bar_left = margin;
  l.bar_right = l.bar_left + 8 * s;
  int widest = text_width(unit, s) - (l.bar_right + 3 * s - margin);
  for (double t : scale.ticks) widest = std::max(widest, text_width(format_scale_value(t), s));
  l.width = l.bar_right + 3 * s + widest + margin;
  return l;
}

int legend_row(const LegendLayout& l, float v) {
  return l.bar_bottom - int(std::lround(double(v) * double(l.bar_bottom - l.bar_top)));
}

Image render_false_colour(std::span<const Vec3> positions, std::span<const float> values,
                          std::span<const uint32_t> indices, const Camera& camera,
                          const RenderOptions& options, const FalseColourScale& scale,
                          std::string_view unit) {
  // Each vertex carries its value and a coverage of 1: after the box filter a pixel holds its
  // covered subsamples' mean value times the coverage, and the coverage itself (faces seen from
  // behind are drawn black, so they count as background).
  std::vector<Vec3> carried(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) carried[v] = Vec3(values[v], 1.0f, 0.0f);
  const Image view = render_image(positions, carried, indices, camera, options);
  const LegendLayout l = legend_layout(scale, unit, options.height);
  Image out(l.width + view.width, view.height);
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const Vec3& p = view.at(x, y);
      if (!(p.y > 0.0f)) continue;
      const float coverage = std::min(p.y, 1.0f);
      out.at(l.width + x, y) =
          coverage * linear_of(false_colour_display(scale_position(scale, p.x / p.y)));
    }
  }
  if (l.width == 0) return out;
  const Vec3 white(1.0f);
  const int s = l.font_scale;
  draw_text(out, l.bar_left, 3 * s, unit, s, white);
  for (int y = l.bar_top; y <= l.bar_bottom; ++y) {
    const float v = float(l.bar_bottom - y) / float(l.bar_bottom - l.bar_top);
    const Vec3 c = linear_of(false_colour_display(v));
    for (int x = l.bar_left; x < l.bar_right; ++x) out.at(x, y) = c;
  }
  // Ticks from the top down, a label wherever it clears the one above it.
  int free_from = 0;
  for (auto t = scale.ticks.rbegin(); t != scale.ticks.rend(); ++t) {
    const int row = legend_row(l, scale_position(scale, *t));
    // Inside the bar's edge: a tick outside it would read as a minus sign before the label.
    for (int y = row - s / 2; y < row - s / 2 + s; ++y)
      for (int x = l.bar_right - 3 * s; x < l.bar_right; ++x) out.at(x, y) = white;
    const int top = row - (kGlyphHeight * s) / 2;
    if (top < free_from) continue;
    draw_text(out, l.bar_right + 3 * s, top, format_scale_value(*t), s, white);
    free_from = top + kGlyphHeight * s + s;
  }
  return out;
}

}  // namespace rad
