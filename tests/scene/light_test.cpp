// Lights' intensity toward a direction (the glTF spot falloff at the values the extension's
// reference formula gives), Light objects of the description format and glTF
// KHR_lights_punctual lights as read, and every error they meet with its location.
#include "scene/light.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "scene/gltf_reader.h"
#include "scene/model_scene.h"
#include "scene/parser.h"
#include "scene_texts.h"

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

// ---- Light objects of the description format ------------------------------------------------

const std::string kFloor =
    "Object \"floor\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0\n"
    "  Data { <-5 0 -5> <-5 0 5> <5 0 5> } }\n";  // lines 2-3 after the scene's name

// The light on line 4 (after the name and the floor) fails at the last `at` in it saying
// `substring`.
void expect_light_error(const std::string& light, const std::string& at,
                        const std::string& substring) {
  const Error e = testing::parse_error("\"s\"\n" + kFloor + light + "\n");
  EXPECT_EQ(e.loc().line, 4) << e.what();
  EXPECT_EQ(e.loc().column, int(light.rfind(at)) + 1) << e.what();
  EXPECT_NE(e.message().find(substring), std::string::npos) << e.what();
}

const Light& light_of(const SceneDescription& s, const std::string& name) {
  for (const ObjectDescription& o : s.objects) {
    if (o.name == name && o.light) return *o.light;
  }
  throw std::runtime_error("no light " + name);
}

TEST(LightDescription, ReadsPointSpotAndDirectionalLightsInDegreesAndUnitDirections) {
  const SceneDescription s = parse_scene_text("\"lit\"\n" + kFloor + R"(
Object "lamp" Light { Type Point Position <0 2 0> Color <1 0.9 0.8> Intensity 100 }
Object "spot" Light { Type Spot Position <1 3 0> Direction <0 -2 0> Intensity 500 Cone 20 30
                      Group "spots" }
Object "sun" Light { Type Directional Direction <-0.3 -1 -0.2> Intensity 100000 }
Object "moon" Light { Type Directional Intensity 0.25 AngularDiameter 0.5 Direction <0 -1 0> }
)",
                                              "scene.des");
  ASSERT_EQ(s.roots.size(), 5u);
  EXPECT_FALSE(s.objects[0].light);
  const Light& lamp = light_of(s, "lamp");
  EXPECT_EQ(lamp.kind, LightKind::Point);
  EXPECT_EQ(lamp.position, Vec3(0, 2, 0));
  EXPECT_EQ(lamp.colour, Vec3(1, 0.9f, 0.8f));
  EXPECT_EQ(lamp.intensity, 100.0f);
  EXPECT_EQ(lamp.photometry, nullptr);
  EXPECT_EQ(lamp.loc.line, 5);
  EXPECT_EQ(lamp.group, "");
  const Light& spot = light_of(s, "spot");
  EXPECT_EQ(spot.kind, LightKind::Spot);
  EXPECT_EQ(spot.direction, Vec3(0, -1, 0));
  EXPECT_NEAR(spot.inner_cone, 20.0f * kDeg, 1e-6f);
  EXPECT_NEAR(spot.outer_cone, 30.0f * kDeg, 1e-6f);
  EXPECT_EQ(spot.group, "spots");
  const Light& sun = light_of(s, "sun");
  EXPECT_EQ(sun.kind, LightKind::Directional);
  EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-6f);
  EXPECT_NEAR(sun.direction.y / sun.direction.x, 1.0f / 0.3f, 1e-4f);
  EXPECT_NEAR(sun.angular_diameter, 0.53f * kDeg, 1e-7f);  // the default
  EXPECT_EQ(sun.intensity, 100000.0f);
  EXPECT_NEAR(light_of(s, "moon").angular_diameter, 0.5f * kDeg, 1e-7f);
}

class LightFiles : public ::testing::Test {
 protected:
  LightFiles()
      : dir(std::filesystem::temp_directory_path() / ("rad_lights_" + std::to_string(getpid()))) {
    std::filesystem::create_directories(dir / "lamps");
  }
  ~LightFiles() override { std::filesystem::remove_all(dir); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  }
  std::filesystem::path dir;
};

// A downlight: 1000 cd at the nadir, half of it at 45 degrees, none at 90.
const char* kDownlight =
    "IESNA:LM-63-2002\n[TEST] t\nTILT=NONE\n1 800 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n1000 500 "
    "0\n";

TEST_F(LightFiles, AnIesFileIsFoundBesideTheDescriptionAndItsTableScaledByIntensity) {
  write("lamps/down.ies", kDownlight);
  const std::string des = write("scene.des", "\"s\"\n" + kFloor + R"(
Object "a" Light { Type Point Position <0 2 0> Ies "lamps/down.ies" }
Object "b" Light { Type Spot Position <1 2 0> Direction <0 -1 0> Cone 40 60 Ies lamps/down.ies
                   Intensity 2 IesC0 <0 0 1> }
)");
  const SceneDescription s = parse_scene_file(des);
  const Light& a = light_of(s, "a");
  const Light& b = light_of(s, "b");
  ASSERT_NE(a.photometry, nullptr);
  EXPECT_EQ(a.photometry, b.photometry) << "one file is read once";
  EXPECT_EQ(a.photometry->lumens(), 800.0f);
  EXPECT_EQ(a.intensity, 1.0f) << "without Intensity, the file's candela as they are";
  EXPECT_EQ(a.direction, Vec3(0, -1, 0)) << "a point light's table hangs straight down";
  EXPECT_NEAR(glm::dot(a.photometric_up, a.direction), 0.0f, 1e-6f);
  EXPECT_EQ(b.photometric_up, Vec3(0, 0, 1));
  EXPECT_NEAR(intensity_toward(a, Vec3(0, -1, 0)), 1000.0f, 1e-3f);
  const Vec3 at45 = glm::normalize(Vec3(1, -1, 0));
  EXPECT_NEAR(intensity_toward(a, at45), 500.0f, 0.5f);
  EXPECT_NEAR(intensity_toward(b, Vec3(0, -1, 0)), 2000.0f, 1e-2f);

  // A missing file is reported at its name; a malformed one at its own line.
  const Error missing = testing::parse_error(
      "\"s\"\n" + kFloor + "Object \"c\" Light { Type Point Position <0 1 0> Ies \"no.ies\" }\n",
      (dir / "scene.des").string());
  EXPECT_EQ(missing.loc().line, 4);
  EXPECT_EQ(missing.loc().column, 52);
  EXPECT_NE(missing.message().find("no such file"), std::string::npos) << missing.what();
  write("lamps/bad.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 800 1 3 1 1 2 0 0 0\n1 1 10\n0 90 45\n");
  const Error bad = testing::parse_error(
      "\"s\"\n" + kFloor + "Object \"c\" Light { Type Point Position <0 1 0> Ies lamps/bad.ies }\n",
      (dir / "scene.des").string());
  EXPECT_EQ(bad.loc().file, (dir / "lamps/bad.ies").string());
  EXPECT_EQ(bad.loc().line, 5);
  EXPECT_NE(bad.message().find("does not increase"), std::string::npos) << bad.what();
}

TEST(LightDescription, EachBadLightIsRefusedAtItsToken) {
  const std::string o = "Object \"l\" Light { ";  // the body starts at column 20
  expect_light_error(o + "Type Point Position <0 1 0> Intensity -5 }", "-5", "negative intensity");
  expect_light_error(o + "Type Point Position <0 1 0> Intensity inf }", "inf", "non-finite number");
  expect_light_error(o + "Type Point Position <0 1 0> Intensity nan }", "nan", "non-finite number");
  expect_light_error(o + "Type Spot Position <0 1 0> Direction <0 0 0> Intensity 1 }", "0 0 0>",
                     "direction is zero");
  expect_light_error(o + "Type Directional Direction <0 0 0> Intensity 1 }", "0 0 0>",
                     "direction is zero");
  expect_light_error(o + "Type Spot Position <0 1 0> Direction <0 -1 0> Intensity 1 Cone 40 30 }",
                     "40", "inner cone (40 degrees) is wider");
  expect_light_error(o + "Type Spot Position <0 1 0> Direction <0 -1 0> Intensity 1 Cone 10 95 }",
                     "95", "at most 90");
  expect_light_error(o + "Type Point Intensity 1 }", "}", "has no Position");
  expect_light_error(o + "Type Spot Position <0 1 0> Intensity 1 }", "}", "has no Direction");
  expect_light_error(o + "Type Point Position <0 1 0> }", "}", "has no Intensity");
  expect_light_error(o + "Type Directional Position <0 1 0> }", "Position",
                     "has no Position: the sun");
  expect_light_error(o + "Type Point Position <0 1 0> Cone 10 20 }", "Cone", "has no Cone");
  expect_light_error(o + "Type Directional Direction <0 -1 0> Intensity 1 AngularDiameter 95 }",
                     "95", "angular diameter 95");
  expect_light_error(o + "Type Point Position <0 1 0> Direction <0 -1 0> Intensity 1 }",
                     "Direction", "shines every way");
  expect_light_error(o + "Type Point Position <0 1 0> Intensity 1 Intensity 2 }", "Intensity",
                     "'Intensity' given twice");
  expect_light_error(o + "Type Point Position <0 1 0> Radius 1 }", "Radius",
                     "unknown keyword 'Radius'");
  expect_light_error(o + "Type Point Position <0 1 0> intensity 1 }", "intensity",
                     "keywords are case-sensitive: 'Intensity'");
  expect_light_error(o + "Type Area Position <0 1 0> }", "Area",
                     "'Point', 'Spot' or 'Directional'");
  expect_light_error(o + "Position <0 1 0> }", "Position", "expected 'Type'");
  expect_light_error(o + "Type Point Position <0 1 0> Color <1 -1 1> Intensity 1 }", "-1",
                     "negative green colour");
  expect_light_error("Object \"l\" Light CastsShadows No { Type Point Position <0 1 0> }", "Light",
                     "a Light takes Translate, Rotate and Scale");
}

// ---- glTF KHR_lights_punctual ------------------------------------------------------------------

// A floor (a 10 m quad at y = 0, facing up), unlit, and the lights and their nodes given.
std::string lit_gltf(const std::string& lights, const std::string& nodes,
                     const std::string& scene_nodes) {
  std::string buf;
  const float p[4][3] = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  buf.append(reinterpret_cast<const char*>(p), sizeof p);
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  buf.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return R"({"asset": {"version": "2.0"}, "scene": 0,
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [)" +
         lights + R"(]}},
    "scenes": [{"nodes": [0, )" +
         scene_nodes + R"(]}],
    "nodes": [{"name": "floor", "mesh": 0}, )" +
         nodes + R"(],
    "meshes": [{"name": "floor", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"name": "Floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [-5, 0, -5], "max": [5, 0, 5]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
         testing::base64(buf) + R"("}]})";
}

const std::string kThreeLights =
    R"({"name": "bulb", "type": "point", "intensity": 100, "color": [1, 0.5, 0.25]},
       {"type": "spot", "intensity": 500, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}},
       {"name": "sun", "type": "directional", "intensity": 100000})";
// The bulb 2 m up; the spot under a parent moved 1 m along x, itself turned -90 degrees about x
// (its -Z axis then points down) and 3 m up; the sun turned so it shines along -x.
const std::string kThreeNodes =
    R"({"name": "bulb node", "translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
       {"name": "rig", "translation": [1, 0, 0], "children": [3]},
       {"name": "spot node", "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
        "extensions": {"KHR_lights_punctual": {"light": 1}}},
       {"name": "sun node", "rotation": [0, 0.70710678, 0, 0.70710678],
        "extensions": {"KHR_lights_punctual": {"light": 2}}})";

TEST(LightGltf, PointSpotAndDirectionalLightsTakeTheirNodesWorldTransforms) {
  const Model m = parse_gltf(lit_gltf(kThreeLights, kThreeNodes, "1, 2, 4"), "lit.gltf", "");
  ASSERT_EQ(m.lights.size(), 3u);
  std::map<std::string, Light> by_name;
  for (const Light& l : m.lights) by_name[l.name] = l;
  ASSERT_EQ(by_name.count("bulb"), 1u);
  ASSERT_EQ(by_name.count("spot node"), 1u) << "an unnamed light takes its node's name";
  ASSERT_EQ(by_name.count("sun"), 1u);
  const Light& bulb = by_name["bulb"];
  EXPECT_EQ(bulb.kind, LightKind::Point);
  EXPECT_EQ(bulb.position, Vec3(0, 2, 0));
  EXPECT_EQ(bulb.intensity, 100.0f);  // candela
  EXPECT_EQ(bulb.colour, Vec3(1, 0.5f, 0.25f));
  const Light& spot = by_name["spot node"];
  EXPECT_EQ(spot.kind, LightKind::Spot);
  EXPECT_NEAR(glm::length(spot.position - Vec3(1, 3, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(spot.direction - Vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(spot.inner_cone, 0.2f, 1e-7f);
  EXPECT_NEAR(spot.outer_cone, 0.4f, 1e-7f);
  EXPECT_EQ(spot.colour, Vec3(1.0f));
  const Light& sun = by_name["sun"];
  EXPECT_EQ(sun.kind, LightKind::Directional);
  EXPECT_NEAR(glm::length(sun.direction - Vec3(-1, 0, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(sun.intensity, 100000.0f);  // lux

  // A model lit by its lights alone needs no --emit, and its hierarchy (regrouped, as a model's
  // is by default) carries them.
  ModelOptions o;
  const SceneDescription d = model_to_scene(m, o);
  const Hierarchy h = build_hierarchy(d);
  EXPECT_EQ(h.lights.size(), 3u);
  const Hierarchy regrouped = build_hierarchy(d, HierarchyMode::Automatic);
  ASSERT_EQ(regrouped.lights.size(), 3u);
  EXPECT_EQ(regrouped.triangles.size(), 2u);
  EXPECT_EQ(regrouped.lights[1].position, h.lights[1].position);
  EXPECT_EQ(build_hierarchy(automatic_hierarchy(h)).lights.size(), 3u);
}

TEST(LightGltf, LightsInADescriptionsModelArePlacedByItsTransforms) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("rad_gltf_lights_" + std::to_string(getpid())))
          .string();
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/lit.gltf") << lit_gltf(kThreeLights, kThreeNodes, "1, 2, 4");
  const Hierarchy h =
      build_hierarchy(parse_scene_text("\"s\"\nObject \"room\" Model lit.gltf Translate <0 0 10>\n"
                                       "Object \"room 2\" Copy \"room\" Translate <0 0 10>\n",
                                       dir + "/scene.des"));
  std::filesystem::remove_all(dir);
  ASSERT_EQ(h.lights.size(), 6u);
  std::vector<Vec3> bulbs;
  for (const Light& l : h.lights) {
    if (l.name == "bulb") bulbs.push_back(l.position);
  }
  EXPECT_EQ(bulbs, (std::vector<Vec3>{Vec3(0, 2, 10), Vec3(0, 2, 20)}));
}

TEST(LightGltf, BadLightsEndInOneErrorNamingTheLight) {
  auto refused = [](const std::string& lights, const std::string& nodes, const std::string& why) {
    try {
      parse_gltf(lit_gltf(lights, nodes, "1"), "bad.gltf", "");
      ADD_FAILURE() << "no error for " << lights << " " << nodes;
    } catch (const Error& e) {
      EXPECT_EQ(e.loc().file, "bad.gltf");
      EXPECT_NE(e.message().find(why), std::string::npos) << e.what();
    }
  };
  const std::string node0 = R"({"extensions": {"KHR_lights_punctual": {"light": 0}}})";
  refused(R"({"type": "point", "intensity": -1})", node0, "negative intensity");
  refused(R"({"type": "area"})", node0, "point, spot or directional");
  refused(R"({"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.3}})", node0,
          "wider than its outer");
  refused(R"({"type": "spot", "spot": {"outerConeAngle": 2.0}})", node0, "beyond 90");
  refused(R"({"type": "point", "color": [1, 1]})", node0, "3 components");
  refused(R"({"type": "point"})", R"({"extensions": {"KHR_lights_punctual": {"light": 3}}})",
          "no such KHR_lights_punctual light");
  refused(R"({"type": "point"})", R"({"extensions": {"KHR_lights_punctual": {"light": 1e300}}})",
          "no such KHR_lights_punctual light");
  refused(R"({"type": "spot", "spot": {}})",
          R"({"scale": [0, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}})",
          "zero length");
  // A range is ignored (with a warning); the defaults are the extension's.
  const Model m = parse_gltf(lit_gltf(R"({"type": "spot", "range": 10, "spot": {}})", node0, "1"),
                             "range.gltf", "");
  ASSERT_EQ(m.lights.size(), 1u);
  EXPECT_EQ(m.lights[0].intensity, 1.0f);
  EXPECT_EQ(m.lights[0].inner_cone, 0.0f);
  EXPECT_NEAR(m.lights[0].outer_cone, std::numbers::pi_v<float> / 4.0f, 1e-6f);
}

}  // namespace
}  // namespace rad
