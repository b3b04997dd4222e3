// False colour images: the palette, the scale chosen from the values, the labels, and a pixel at
// a known illuminance showing the colour the legend gives that illuminance.
#include "export/false_colour.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "export/tonemap.h"

namespace rad {
namespace {

TEST(FalseColour, PaletteRunsFromDarkBlueThroughGreenAndYellowToRed) {
  const Vec3 bottom = false_colour_display(0.0f), top = false_colour_display(1.0f);
  EXPECT_GT(bottom.z, 0.1f);  // dark blue: apart from a black background
  EXPECT_LT(max_component(bottom), 0.5f);
  EXPECT_EQ(bottom.x, 0.0f);
  EXPECT_EQ(bottom.y, 0.0f);
  EXPECT_GT(top.x, 0.8f);  // red
  EXPECT_LT(top.y, 0.1f);
  EXPECT_LT(top.z, 0.1f);
  const Vec3 green = false_colour_display(0.48f), yellow = false_colour_display(0.66f);
  EXPECT_GT(green.y, 2.0f * std::max(green.x, green.z));
  EXPECT_GT(yellow.x, 0.8f);
  EXPECT_GT(yellow.y, 0.8f);
  EXPECT_LT(yellow.z, 0.1f);
  // Clamped outside [0, 1]; continuous inside.
  EXPECT_EQ(false_colour_display(-1.0f), bottom);
  EXPECT_EQ(false_colour_display(2.0f), top);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = false_colour_display(float(i) / 1000),
               b = false_colour_display(float(i + 1) / 1000);
    EXPECT_LT(max_component(glm::abs(a - b)), 0.01f) << i;
  }
}

TEST(FalseColour, TheScaleTopsAtARoundNumberAboveThe99thPercentile) {
  std::vector<float> lux;
  for (int i = 1; i <= 1000; ++i) lux.push_back(float(i));  // 99th percentile: 991
  EXPECT_EQ(round_scale_max(lux), 1000.0);
  // A few hot spots (the vertices under a lamp) do not set the scale.
  std::vector<float> room(1000, 123.0f);
  room.insert(room.end(), 5, 1e6f);
  EXPECT_EQ(round_scale_max(room), 150.0);
  EXPECT_EQ(round_scale_max(std::vector<float>{0.0f, -1.0f}), 1.0);  // unlit
  EXPECT_NEAR(round_scale_max(std::vector<float>{0.031f}), 0.04, 1e-12);

  FalseColourScale s = make_false_colour_scale(lux, {});
  ASSERT_EQ(s.ticks.size(), 11u);  // 0, 100, ..., 1000
  EXPECT_EQ(s.ticks[3], 300.0);
  EXPECT_EQ(s.ticks.back(), 1000.0);
  EXPECT_FLOAT_EQ(scale_position(s, 250.0), 0.25f);
  EXPECT_EQ(scale_position(s, 5000.0), 1.0f);
  EXPECT_EQ(scale_position(s, 0.0), 0.0f);
  s = make_false_colour_scale(lux, {.max = 1500.0});
  EXPECT_EQ(s.ticks.size(), 7u);  // steps of 250
  s = make_false_colour_scale(lux, {.max = 750.0});
  EXPECT_EQ(s.ticks.size(), 9u);  // no round step: Radiance's 8

  // Logarithmic: Radiance's log10(value / max) / decades + 1, a tick at each decade.
  s = make_false_colour_scale(lux, {.max = 1000.0, .log_decades = 3});
  EXPECT_EQ(s.ticks, (std::vector<double>{1.0, 10.0, 100.0, 1000.0}));
  EXPECT_NEAR(scale_position(s, 10.0), 1.0f / 3.0f, 1e-6);
  EXPECT_EQ(scale_position(s, 0.5), 0.0f);
  s = make_false_colour_scale(lux, {.max = 100.0, .log_decades = 1});
  EXPECT_EQ(s.ticks, (std::vector<double>{10.0, 20.0, 50.0, 100.0}));

  EXPECT_THROW(make_false_colour_scale(lux, {.max = -1.0}), Error);
  EXPECT_THROW(make_false_colour_scale(lux, {.max = NAN}), Error);
  EXPECT_THROW(make_false_colour_scale(lux, {.log_decades = kMaxFalseColourDecades + 1}), Error);
}

TEST(FalseColour, LabelsAreShortAndRound) {
  EXPECT_EQ(format_scale_value(0.0), "0");
  EXPECT_EQ(format_scale_value(0.25), "0.25");
  EXPECT_EQ(format_scale_value(62.5), "62.5");
  EXPECT_EQ(format_scale_value(187.5), "187.5");
  EXPECT_EQ(format_scale_value(1000.0), "1000");
  EXPECT_EQ(format_scale_value(12500.0), "12.5k");
  EXPECT_EQ(format_scale_value(100000.0), "100k");
  EXPECT_EQ(format_scale_value(2.5e7), "25M");
  EXPECT_EQ(format_scale_value(1e-7), "1e-07");
}

TEST(FalseColour, LuminanceWeighsTheChannelsPhotometrically) {
  EXPECT_FLOAT_EQ(luminance_of(Vec3(100.0f)), 100.0f);
  EXPECT_FLOAT_EQ(luminance_of(Vec3(0.0f, 1.0f, 0.0f)), 0.7152f);
}

// Two walls facing the camera, filling the view: 200 lx on the image's left, 800 lx on its right.
struct Walls {
  std::vector<Vec3> position;
  std::vector<float> lux;
  std::vector<uint32_t> indices;
  Camera camera;
  RenderOptions options{.width = 120, .height = 90, .samples = 4};

  Walls() {
    add(0.0f, 4.0f, 200.0f);  // +x is the image's left, seen from -z
    add(-4.0f, 0.0f, 800.0f);
    camera.eye = Vec3(0.0f, 0.0f, -1.0f);
    camera.target = Vec3(0.0f);
    camera.fov_y_deg = 60.0f;
  }
  void add(float x0, float x1, float value) {
    const uint32_t n = uint32_t(position.size());
    // Their fronts face -z, toward the eye.
    for (const Vec3& p : {Vec3(x0, -4, 0), Vec3(x0, 4, 0), Vec3(x1, 4, 0), Vec3(x1, -4, 0)}) {
      position.push_back(p);
      lux.push_back(value);
    }
    indices.insert(indices.end(), {n, n + 1, n + 2, n, n + 2, n + 3});
  }
};

Vec3 displayed(const Vec3& linear) {
  return Vec3(srgb_encode(linear.x), srgb_encode(linear.y), srgb_encode(linear.z));
}

void expect_near(const Vec3& a, const Vec3& b, float tolerance, const std::string& what) {
  EXPECT_LT(max_component(glm::abs(a - b)), tolerance)
      << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") against (" << b.x << ", " << b.y
      << ", " << b.z << ")";
}

TEST(FalseColour, APixelAtAKnownIlluminanceHasTheLegendsColourForIt) {
  const Walls w;
  const FalseColourScale scale = make_false_colour_scale(w.lux, {.max = 1000.0});
  const Image img =
      render_false_colour(w.position, w.lux, w.indices, w.camera, w.options, scale, "lx");
  const LegendLayout l = legend_layout(scale, "lx", w.options.height);
  ASSERT_GT(l.width, 0);
  ASSERT_EQ(img.width, l.width + w.options.width);
  ASSERT_EQ(img.height, w.options.height);
  const int y = w.options.height / 2;
  for (const auto& [x, lux] :
       {std::pair{w.options.width / 4, 200.0}, {3 * w.options.width / 4, 800.0}}) {
    const Vec3 pixel = displayed(img.at(l.width + x, y));
    const float v = scale_position(scale, lux);
    expect_near(pixel, false_colour_display(v), 1e-4f, "the wall at " + std::to_string(lux));
    // The legend's bar, on the row of that value, shows the same colour (within a row's step).
    const Vec3 legend = displayed(img.at(l.bar_left + l.font_scale, legend_row(l, v)));
    expect_near(pixel, legend, 0.03f, "the legend at " + std::to_string(lux));
  }
  // The walls differ, and neither is the legend's colour for the other.
  EXPECT_GT(max_component(glm::abs(displayed(img.at(l.width + 10, y)) -
                                   displayed(img.at(img.width - 10, y)))),
            0.3f);
  // A label beside each tick: white pixels right of the bar, on the tick's rows.
  for (double t : scale.ticks) {
    const int row = legend_row(l, scale_position(scale, t));
    int white = 0;
    for (int yy = row - 4 * l.font_scale; yy <= row + 4 * l.font_scale; ++yy) {
      for (int x = l.bar_right + 3 * l.font_scale; x < l.width; ++x)
        white += yy >= 0 && yy < img.height && img.at(x, yy) == Vec3(1.0f);
    }
    EXPECT_GT(white, 0) << "no label at " << t;
  }
  // The unit, above the bar.
  int unit = 0;
  for (int yy = 0; yy < l.bar_top - 4 * l.font_scale; ++yy)
    for (int x = 0; x < l.width; ++x) unit += img.at(x, yy) == Vec3(1.0f);
  EXPECT_GT(unit, 10);
}

TEST(FalseColour, TheBackgroundStaysBlackAndALowImageHasNoLegend) {
  Walls w;
  w.camera.eye = Vec3(0.0f, 0.0f, 1.0f);  // behind the walls: their backs, drawn as background
  w.camera.target = Vec3(0.0f, 0.0f, 2.0f);
  const FalseColourScale scale = make_false_colour_scale(w.lux, {});
  const Image img =
      render_false_colour(w.position, w.lux, w.indices, w.camera, w.options, scale, "lx");
  const int left = legend_layout(scale, "lx", w.options.height).width;
  for (int y = 0; y < img.height; ++y)
    for (int x = left; x < img.width; ++x) ASSERT_EQ(img.at(x, y), Vec3(0.0f)) << x << "," << y;
  EXPECT_EQ(legend_layout(scale, "lx", 30).width, 0);
}

}  // namespace
}  // namespace rad
