// --stage: the floor under a model, the light above it, their levels, and the same stage up to
// scale for a model scaled or moved; --sun's angles.
#include "scene/stage.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "scene/description.h"
#include "scene/scene_file.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// A box 2 wide (x), 1 high, 1 deep standing on y = 0 around the origin, scaled and moved.
Aabb box(float scale, Vec3 at) {
  Aabb b;
  b.extend(at + scale * Vec3(-1.0f, 0.0f, -0.5f));
  b.extend(at + scale * Vec3(1.0f, 1.0f, 0.5f));
  return b;
}

// The illuminance the light gives a point of the floor straight under its centre, unoccluded,
// integrated over the light's area (midpoint rule): E = M / pi * sum cos^2 / r^2 dA.
double illuminance_below(const Stage& s) {
  const int n = 400;
  const Vec2 size = s.light_hi - s.light_lo, centre = 0.5f * (s.light_lo + s.light_hi);
  const double h = double(s.light_y) - double(s.floor_y);
  const double da = double(size.x) * double(size.y) / (n * n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = double(s.light_lo.x) + (i + 0.5) * size.x / n - centre.x;
      const double z = double(s.light_lo.y) + (j + 0.5) * size.y / n - centre.y;
      const double r2 = x * x + z * z + h * h;
      sum += h * h / (r2 * r2) * da;
    }
  }
  return double(s.exitance) / std::numbers::pi * sum;
}

TEST(Stage, TheFloorIsUnderTheModelAndTheLightAboveIt) {
  const Aabb b = box(1.0f, Vec3(0.0f));
  const Stage s = plan_stage(b, {});
  EXPECT_EQ(s.floor_y, b.lo.y);
  // Beyond the footprint on every side, and not much: "slightly larger".
  EXPECT_LT(s.floor_lo.x, b.lo.x);
  EXPECT_LT(s.floor_lo.y, b.lo.z);
  EXPECT_GT(s.floor_hi.x, b.hi.x);
  EXPECT_GT(s.floor_hi.y, b.hi.z);
  EXPECT_LT(s.floor_hi.x - s.floor_lo.x, 2.0f * (b.hi.x - b.lo.x));
  // Above the top, over the footprint's centre (moved toward the camera's side, front right),
  // at least as wide as the footprint.
  EXPECT_GT(s.light_y, b.hi.y);
  const Vec2 centre = 0.5f * (s.light_lo + s.light_hi);
  EXPECT_GT(centre.x, 0.0f);
  EXPECT_GT(centre.y, 0.0f);
  EXPECT_LT(s.light_lo.x, 0.0f);
  EXPECT_LT(s.light_lo.y, 0.0f);
  EXPECT_GE(s.light_hi.x - s.light_lo.x, b.hi.x - b.lo.x);
  EXPECT_GE(s.light_hi.y - s.light_lo.y, b.hi.z - b.lo.z);
  EXPECT_FALSE(s.sun);
  // Its exitance gives the floor below it the stated illuminance.
  EXPECT_EQ(s.illuminance_below, kStageIlluminance);
  EXPECT_NEAR(illuminance_below(s), kStageIlluminance, 1e-3 * kStageIlluminance);
  // The camera sees it from the front (+z), to the right (+x) and above.
  EXPECT_NEAR(glm::length(s.view_direction), 1.0f, 1e-6f);
  EXPECT_GT(s.view_direction.x, 0.0f);
  EXPECT_GT(s.view_direction.y, 0.0f);
  EXPECT_GT(s.view_direction.z, s.view_direction.x);
}

TEST(Stage, AModelScaledOrMovedGetsTheSameStageUpToThatScale) {
  const Stage one = plan_stage(box(1.0f, Vec3(0.0f)), {.sun = SunAngles{}});
  for (const float scale : {0.01f, 100.0f}) {
    const Vec3 at(3.0f * scale, -7.0f * scale, 11.0f * scale);
    const Stage s = plan_stage(box(scale, at), {.sun = SunAngles{}});
    const float tol = 1e-5f * scale;
    EXPECT_NEAR(s.floor_y, at.y, 10.0f * tol);
    EXPECT_NEAR(s.light_y - at.y, scale * one.light_y, 10.0f * tol);
    for (int k = 0; k < 2; ++k) {
      const float shift = k == 0 ? at.x : at.z;
      EXPECT_NEAR(s.floor_lo[k] - shift, scale * one.floor_lo[k], 10.0f * tol);
      EXPECT_NEAR(s.floor_hi[k] - shift, scale * one.floor_hi[k], 10.0f * tol);
      EXPECT_NEAR(s.light_lo[k] - shift, scale * one.light_lo[k], 10.0f * tol);
      EXPECT_NEAR(s.light_hi[k] - shift, scale * one.light_hi[k], 10.0f * tol);
    }
    // Lights of the same strength: the floor, the model and the picture are lit alike.
    EXPECT_NEAR(s.exitance, one.exitance, 1e-4f * one.exitance);
    EXPECT_EQ(s.sun_illuminance, one.sun_illuminance);
    EXPECT_EQ(s.sun_direction, one.sun_direction);
    EXPECT_EQ(s.view_direction, one.view_direction);
  }
}

TEST(Stage, TheSunShinesFromItsAnglesAndTheFloorHoldsTheShadow) {
  const Aabb b = box(1.0f, Vec3(0.0f));
  const Stage s = plan_stage(b, {.sun = SunAngles{30.0f, 90.0f}});  // low, from +x
  ASSERT_TRUE(s.sun);
  EXPECT_EQ(s.sun_illuminance, kStageSunIlluminance);
  EXPECT_EQ(s.illuminance_below, kStageSkyIlluminance);
  EXPECT_NEAR(s.sun_direction.x, -std::cos(30.0f * std::numbers::pi_v<float> / 180.0f), 1e-6f);
  EXPECT_NEAR(s.sun_direction.y, -0.5f, 1e-6f);
  EXPECT_NEAR(s.sun_direction.z, 0.0f, 1e-6f);
  // The top's shadow falls 1 / tan 30 = 1.73 beyond the box toward -x: the floor reaches it.
  EXPECT_LT(s.floor_lo.x, b.lo.x - std::sqrt(3.0f));
  EXPECT_NEAR(illuminance_below(s), kStageSkyIlluminance, 1e-3 * kStageSkyIlluminance);
}

TEST(Stage, AFlatOrThinModelStillGetsAFloorAndALightAboveIt) {
  Aabb flat;  // a rug: no height
  flat.extend(Vec3(0.0f));
  flat.extend(Vec3(4.0f, 0.0f, 3.0f));
  const Stage rug = plan_stage(flat, {});
  EXPECT_GT(rug.light_y, 0.0f);
  EXPECT_LT(rug.floor_lo.x, 0.0f);
  Aabb pole;  // a lamp post
  pole.extend(Vec3(0.0f));
  pole.extend(Vec3(0.1f, 3.0f, 0.1f));
  const Stage post = plan_stage(pole, {});
  EXPECT_GT(post.light_y, 3.0f);
  EXPECT_GT(post.floor_hi.x - post.floor_lo.x, 1.0f);  // room for its shadow
  EXPECT_GT(post.light_hi.x - post.light_lo.x, 1.0f);  // no sliver of a light
  EXPECT_THROW(plan_stage(Aabb{}, {}), Error);
}

TEST(Stage, SunAnglesAreElevationCommaAzimuth) {
  const SunAngles d = parse_sun_angles("");
  EXPECT_EQ(d.elevation_deg, SunAngles{}.elevation_deg);
  EXPECT_EQ(d.azimuth_deg, SunAngles{}.azimuth_deg);
  const SunAngles s = parse_sun_angles("30,-120.5");
  EXPECT_EQ(s.elevation_deg, 30.0f);
  EXPECT_EQ(s.azimuth_deg, -120.5f);
  for (const char* bad : {"30", "30,", ",20", "a,b", "model.glb", "0,10", "-5,10", "91,0", "45,400",
                          "45,10,3", "nan,0"}) {
    try {
      parse_sun_angles(bad);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(e.message().find("--sun"), std::string::npos) << e.message();
    }
  }
}

// read_scene_file with a stage: the model's scene plus the stage's objects, and no refusal of a
// model with nothing emitting (the stage lights it).
TEST(Stage, AStagedModelKeepsItsObjectsAndGainsTheStage) {
  const fs::path obj =
      fs::temp_directory_path() / ("rad_stage_" + std::to_string(getpid()) + ".obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  ModelOptions o;
  EXPECT_THROW(read_scene_file(obj.string(), o), Error);  // nothing emits
  o.stage = StageOptions{.sun = SunAngles{}};
  const SceneDescription d = read_scene_file(obj.string(), o);
  fs::remove(obj);
  ASSERT_TRUE(d.model && d.model->stage);
  const Stage& s = *d.model->stage;
  EXPECT_EQ(s.model.lo, Vec3(0.0f));
  EXPECT_EQ(s.model.hi, Vec3(1.0f, 1.0f, 0.0f));
  const ObjectDescription* floor = nullptr;
  const ObjectDescription* light = nullptr;
  const ObjectDescription* sun = nullptr;
  for (const ObjectDescription& x : d.objects) {
    if (x.name == "stage floor") floor = &x;
    if (x.name == "stage light") light = &x;
    if (x.name == "stage sun") sun = &x;
  }
  ASSERT_TRUE(floor && light && sun);
  ASSERT_EQ(floor->triangles.size(), 2u);
  for (const auto& t : floor->triangles) {  // facing up, at the model's foot
    EXPECT_GT(glm::cross(t[1] - t[0], t[2] - t[0]).y, 0.0f);
    EXPECT_EQ(t[0].y, 0.0f);
  }
  for (const auto& t : light->triangles) {  // facing down, above it
    EXPECT_LT(glm::cross(t[1] - t[0], t[2] - t[0]).y, 0.0f);
    EXPECT_GT(t[0].y, 1.0f);
  }
  EXPECT_EQ(floor->material.reflectance, Vec3(kStageFloorReflectance));
  EXPECT_EQ(light->material.emission, Vec3(s.exitance));
  ASSERT_TRUE(sun->light);
  EXPECT_EQ(sun->light->kind, LightKind::Directional);
  EXPECT_EQ(sun->light->intensity, kStageSunIlluminance);
  const std::string line = describe_stage(s, 1.0);
  EXPECT_EQ(line.rfind("Stage: floor ", 0), 0u) << line;
  EXPECT_NE(line.find("Emission"), std::string::npos) << line;
  EXPECT_NE(line.find(" lm"), std::string::npos) << line;
  EXPECT_NE(line.find("sun at elevation 45"), std::string::npos) << line;
}

}  // namespace
}  // namespace rad
