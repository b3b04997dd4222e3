// Lights' intensity toward a direction: the glTF spot falloff at the values the extension's
// reference formula gives.
#include "scene/light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rad {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

TEST(Light, TheSpotFalloffIsTheSquaredRampInCosineBetweenTheCones) {
  const float inner = 20.0f * kDeg, outer = 30.0f * kDeg;
  EXPECT_EQ(spot_falloff(1.0f, inner, outer), 1.0f);
  EXPECT_EQ(spot_falloff(std::cos(inner), inner, outer), 1.0f);
  EXPECT_EQ(spot_falloff(std::cos(outer), inner, outer), 0.0f);
  EXPECT_EQ(spot_falloff(std::cos(40.0f * kDeg), inner, outer), 0.0f);
  const float c = 0.5f * (std::cos(inner) + std::cos(outer));  // halfway in cosine
  EXPECT_NEAR(spot_falloff(c, inner, outer), 0.25f, 1e-5f);
  // Equal cones: a step 0.001 wide in cosine, not a division by zero.
  EXPECT_EQ(spot_falloff(std::cos(inner) + 2e-3f, inner, inner), 1.0f);
  EXPECT_EQ(spot_falloff(std::cos(inner) - 1e-6f, inner, inner), 0.0f);
}

TEST(Light, APointLightIsTheSameEverywhereAndASpotFollowsItsAxis) {
  Light point;
  point.intensity = 40.0f;
  EXPECT_EQ(intensity_toward(point, Vec3(0, 1, 0)), 40.0f);
  EXPECT_EQ(intensity_toward(point, Vec3(1, 0, 0)), 40.0f);
  Light spot = point;
  spot.kind = LightKind::Spot;
  spot.direction = Vec3(0, 0, -2);  // not unit: the axis counts, not its length
  spot.inner_cone = 10.0f * kDeg, spot.outer_cone = 20.0f * kDeg;
  EXPECT_EQ(intensity_toward(spot, Vec3(0, 0, -1)), 40.0f);
  EXPECT_EQ(intensity_toward(spot, Vec3(0, 0, 1)), 0.0f);
  const Vec3 at15(std::sin(15.0f * kDeg), 0.0f, -std::cos(15.0f * kDeg));
  const float t = (std::cos(15.0f * kDeg) - std::cos(20.0f * kDeg)) /
                  (std::cos(10.0f * kDeg) - std::cos(20.0f * kDeg));
  EXPECT_NEAR(intensity_toward(spot, at15), 40.0f * t * t, 1e-4f);
}

}  // namespace
}  // namespace rad
