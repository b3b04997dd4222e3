#include "export/exposure.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

/// 100 grey surfaces at 0.01 .. 1.00 and one light at 50 (alone it would set the exposure).
std::vector<Vec3> lit_room() {
  std::vector<Vec3> display;
  for (int i = 1; i <= 100; ++i) display.push_back(Vec3(0.01f * float(i)));
  display.push_back(Vec3(50.0f));
  return display;
}

SolverState with_emission(Vec3 e) {
  SolverState s;
  s.solution.materials = {Material{Vec3(0.5f), Vec3(0.0f)}, Material{Vec3(0.0f), e}};
  return s;
}

TEST(Exposure, IgnoresLightSourcesAndMapsThe99thPercentileToOne) {
  const ToneMap tm = scene_tone_map(with_emission(Vec3(50.0f)), lit_room(), ToneCurve::Aces, 0);
  EXPECT_EQ(tm.curve, ToneCurve::Aces);
  EXPECT_NEAR(tm.scale, 1.0f, 1e-6f);  // the 99th of 100 values is the largest, 1.0
  // One stop more doubles it.
  EXPECT_NEAR(scene_tone_map(with_emission(Vec3(50.0f)), lit_room(), ToneCurve::Clamp, 1).scale,
              2.0f, 1e-6f);
}

TEST(Exposure, UsesEveryValueWhenEverySurfaceEmits) {
  const std::vector<Vec3> furnace(10, Vec3(2.0f));
  EXPECT_NEAR(scene_tone_map(with_emission(Vec3(1.0f)), furnace, ToneCurve::Clamp, 0).scale, 0.5f,
              1e-6f);
}

}  // namespace
}  // namespace rad
