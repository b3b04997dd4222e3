// Every request is validated: malformed JSON, unknown fields and objects, values out of range
// become BadRequest with a message for the client.
#include "serve/requests.h"

#include <gtest/gtest.h>

#include "serve/material_controls.h"
#include "serve_scene.h"

namespace rad {
namespace {

class Requests : public ::testing::Test {
 protected:
  const Hierarchy h = build_hierarchy(testing::serve_scene());
  const std::string lamp = std::to_string(testing::object_named(h, "lamp"));

  // The message of the BadRequest `f` throws ("" if it does not throw).
  template <class F>
  static std::string rejection(F f) {
    try {
      f();
    } catch (const BadRequest& e) {
      return e.what();
    }
    return "";
  }
  std::string material_error(const std::string& body) const {
    return rejection([&] { parse_material_request(body, h); });
  }
};

TEST_F(Requests, MaterialAcceptsAnyOfTheThreeControls) {
  const MaterialRequest r = parse_material_request(
      R"({"object": )" + lamp + R"(, "colour": [1, 0.5, 0], "emission": 12.5})", h);
  EXPECT_EQ(r.object, testing::object_named(h, "lamp"));
  ASSERT_TRUE(r.patch.colour);
  EXPECT_EQ(*r.patch.colour, Vec3(1.0f, 0.5f, 0.0f));
  EXPECT_FALSE(r.patch.reflectivity);
  EXPECT_FLOAT_EQ(*r.patch.emission, 12.5f);
  EXPECT_TRUE(
      parse_material_request(R"({"object": )" + lamp + R"(, "color": [0,0,0]})", h).patch.colour);
}

TEST_F(Requests, MaterialRejectsMalformedJson) {
  EXPECT_EQ(material_error("{\"object\": 1,"), "malformed JSON");
  EXPECT_EQ(material_error(""), "expected a JSON object, got an empty body");
  EXPECT_EQ(material_error("[1, 2]"), "expected a JSON object");
  EXPECT_EQ(material_error("\"lamp\""), "expected a JSON object");
}

TEST_F(Requests, MaterialRejectsUnknownMissingAndMistypedFields) {
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "colr": [1,1,1]})"),
            "unknown field 'colr'");
  EXPECT_EQ(material_error(R"({"emission": 1})"), "missing field 'object'");
  EXPECT_EQ(material_error(R"({"object": "lamp", "emission": 1})"), "'object' must be an integer");
  EXPECT_EQ(material_error(R"({"object": 1.5, "emission": 1})"), "'object' must be an integer");
  EXPECT_EQ(material_error(R"({"object": true, "emission": 1})"), "'object' must be an integer");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + "}"),
            "nothing to change: give 'colour', 'reflectivity' or 'emission'");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "emission": "5"})"),
            "'emission' must be a number");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "colour": [1, 1]})"),
            "'colour' must be an array of 3 numbers");
  EXPECT_EQ(
      material_error(R"({"object": )" + lamp + R"(, "colour": [1, 1, 1], "color": [1, 1, 1]})"),
      "give 'colour' or 'color', not both");
}

TEST_F(Requests, MaterialRejectsUnknownObjectsAndNonPures) {
  EXPECT_EQ(material_error(R"({"object": 99, "emission": 1})"),
            "'object' is 99; it must be in [0, 8]");
  EXPECT_EQ(material_error(R"({"object": -1, "emission": 1})"),
            "'object' is -1; it must be in [0, 8]");
  EXPECT_EQ(material_error(R"({"object": 18446744073709551615, "emission": 1})"),
            "'object' is 9223372036854775807; it must be in [0, 8]");
  const std::string room = std::to_string(testing::object_named(h, "room"));
  EXPECT_EQ(material_error(R"({"object": )" + room + R"(, "emission": 1})"),
            "object " + room + " ('room') is an Assembly: only Pures have a material");
  const std::string walls = std::to_string(testing::object_named(h, "walls"));
  EXPECT_EQ(material_error(R"({"object": )" + walls + R"(, "emission": 1})"),
            "object " + walls + " ('walls') is a Composite: only Pures have a material");
}

TEST_F(Requests, MaterialRejectsValuesOutOfRange) {
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "reflectivity": 1.01})"),
            "'reflectivity' is 1.01; it must be in [0, 1]");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "emission": -1})"),
            "'emission' is -1; it must be in [0, 1e+07]");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "emission": 1e300})"),
            "'emission' is 1e+300; it must be in [0, 1e+07]");
  EXPECT_EQ(material_error(R"({"object": )" + lamp + R"(, "colour": [0, 2, 0]})"),
            "colour[1] is 2; it must be in [0, 1]");
}

TEST_F(Requests, SubdivideNeedsAPolygonOfTheScene) {
  EXPECT_EQ(parse_subdivide_request(R"({"polygon": 3})", h), 3);
  EXPECT_EQ(rejection([&] { parse_subdivide_request(R"({"polygon": 14})", h); }),
            "'polygon' is 14; it must be in [0, 13]");
  EXPECT_EQ(rejection([&] { parse_subdivide_request(R"({"polygon": 3, "depth": 2})", h); }),
            "unknown field 'depth'");
  EXPECT_EQ(rejection([&] { parse_subdivide_request("{}", h); }), "missing field 'polygon'");
}

TEST_F(Requests, RestartTakesAnEmptyBodyOrWhichMaterials) {
  EXPECT_FALSE(parse_restart_request(""));
  EXPECT_FALSE(parse_restart_request("{}"));
  EXPECT_FALSE(parse_restart_request(R"({"materials": "current"})"));
  EXPECT_TRUE(parse_restart_request(R"({"materials": "original"})"));
  EXPECT_EQ(rejection([] { parse_restart_request(R"({"materials": 1})"); }),
            "'materials' must be \"current\" or \"original\"");
}

TEST_F(Requests, ExposureTakesStopsOrARefit) {
  EXPECT_FLOAT_EQ(*parse_exposure_request(R"({"stops": -1.5})").stops, -1.5f);
  EXPECT_TRUE(parse_exposure_request(R"({"refit": true})").refit);
  EXPECT_EQ(rejection([] { parse_exposure_request(R"({"stops": 21})"); }),
            "'stops' is 21; it must be in [-20, 20]");
  EXPECT_EQ(rejection([] { parse_exposure_request(R"({"refit": 1})"); }),
            "'refit' must be true or false");
  EXPECT_EQ(rejection([] { parse_exposure_request("{}"); }),
            "nothing to change: give 'stops' or 'refit': true");
}

TEST_F(Requests, DimmersTakeOneFactorPerLightGroup) {
  EXPECT_EQ(parse_dimmers_request(R"({"dimmers": [0, 1.5]})", 2), (std::vector<float>{0.0f, 1.5f}));
  EXPECT_EQ(rejection([] { parse_dimmers_request(R"({"dimmers": [1]})", 2); }),
            "'dimmers' must be an array of 2 numbers, one per light group");
  EXPECT_EQ(rejection([] { parse_dimmers_request(R"({"dimmers": [1, -1]})", 2); }),
            "'dimmers'[1] is -1; it must be in [0, 100]");
  EXPECT_NE(
      rejection([] { parse_dimmers_request(R"({"dimmers": []})", 0); }).find("no light groups"),
      std::string::npos);
}

TEST_F(Requests, ExportChecksFormatAndParameters) {
  EXPECT_EQ(parse_export_request("glb", {}).format, ExportFormat::Glb);
  const ExportRequest png =
      parse_export_request("png", {{"camera", "0.5,0.5,-2,0.5,0.5,0.5,40"}, {"size", "320x200"}});
  EXPECT_EQ(png.format, ExportFormat::Png);
  ASSERT_TRUE(png.camera);
  EXPECT_FLOAT_EQ(png.camera->fov_y_deg, 40.0f);
  EXPECT_EQ(png.width, 320);
  EXPECT_EQ(png.height, 200);
  EXPECT_EQ(rejection([] { parse_export_request("exe", {}); }),
            "unknown export format 'exe': ply, off, obj, gltf, glb or png");
  EXPECT_EQ(rejection([] {
              parse_export_request("ply", {{"size", "10x10"}});
            }),
            "unknown parameter 'size' (camera and size are for png)");
  EXPECT_EQ(rejection([] {
              parse_export_request("png", {{"path", "/etc/passwd"}});
            }),
            "unknown parameter 'path': camera or size");
  EXPECT_EQ(rejection([] {
              parse_export_request("png", {{"size", "8x8"}});
            }),
            "size: expected WxH, 16 to 4096 pixels each, got '8x8'");
  EXPECT_EQ(rejection([] {
              parse_export_request("png", {{"size", "64x64"}, {"size", "32x32"}});
            }),
            "parameter 'size' given twice");
  EXPECT_EQ(rejection([] {
              parse_export_request("png", {{"camera", "1,2,3,1,2,3"}});
            }),
            "camera: the eye and the target are the same point");
}

TEST(LightRequests, TakeColourOrIntensityOfAnyLightOfTheScene) {
  Hierarchy h = build_hierarchy(testing::serve_scene());
  Light on, off;
  on.intensity = 10.0f;
  off.name = "spare";
  h.lights = {on, off};
  const LightRequest r = parse_light_request(R"({"light": 0, "intensity": 25.5})", h);
  EXPECT_EQ(r.light, 0);
  EXPECT_EQ(r.patch.intensity, 25.5f);
  EXPECT_FALSE(r.patch.colour);
  const LightRequest c = parse_light_request(R"({"light": 0, "color": [1, 0.5, 0]})", h);
  EXPECT_EQ(c.patch.colour, Vec3(1.0f, 0.5f, 0.0f));
  auto error = [&](const std::string& body) -> std::string {
    try {
      parse_light_request(body, h);
    } catch (const BadRequest& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(parse_light_request(R"({"light": 1, "intensity": 1})", h).patch.intensity, 1.0f)
      << "a light the scene leaves off can be turned on";
  EXPECT_NE(error(R"({"light": 2, "intensity": 1})").find("'light' is 2"), std::string::npos);
  EXPECT_NE(error(R"({"light": 0})").find("nothing to change"), std::string::npos);
  EXPECT_NE(error(R"({"light": 0, "intensity": -1})").find("'intensity'"), std::string::npos);
  EXPECT_NE(error(R"({"light": 0, "intensity": 1e10})").find("'intensity'"), std::string::npos);
  EXPECT_NE(error(R"({"light": 0, "colour": [1, 2, 0]})").find("colour[1]"), std::string::npos);
  EXPECT_NE(error(R"({"light": 0, "watts": 3})").find("unknown field 'watts'"), std::string::npos);
  h.lights.clear();
  EXPECT_NE(error(R"({"light": 0, "intensity": 1})").find("no lights"), std::string::npos);
}

TEST(LightControls, ShowCandelaWhateverTheSceneUnitAndKeepColourTimesIntensity) {
  Light l;
  l.kind = LightKind::Point;
  l.colour = Vec3(2.0f, 1.0f, 0.5f);
  l.intensity = 3.0f;                                 // candela per square unit
  const LightControls c = to_light_controls(l, 4.0);  // 2 m per unit
  EXPECT_EQ(c.colour, Vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(c.intensity, 24.0f);
  const LightSetting back = to_light_setting(c, l.kind, 4.0);
  EXPECT_FLOAT_EQ(back.intensity * back.colour.x, 6.0f);
  l.kind = LightKind::Directional;  // lux: no unit of length in it
  EXPECT_FLOAT_EQ(to_light_controls(l, 4.0).intensity, 6.0f);
  EXPECT_STREQ(intensity_unit(LightKind::Spot), "cd");
  EXPECT_STREQ(intensity_unit(LightKind::Directional), "lx");
}

TEST(MaterialControls, SplitAndJoinMaterialsAsTheDescriptionWritesThem) {
  // The Cornell box light: Reflectivity 0.78 Color <1 0.70588 0.23529> Emission 53.407.
  const Vec3 c(1.0f, 0.70588f, 0.23529f);
  const Material light{0.78f * c, 53.407f * c};
  const MaterialControls k = to_controls(light);
  EXPECT_NEAR(k.colour.y, 0.70588f, 1e-6f);
  EXPECT_NEAR(k.reflectivity, 0.78f, 1e-6f);
  EXPECT_NEAR(k.emission, 53.407f, 1e-4f);
  const Material back = to_material(k);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(back.reflectance[i], light.reflectance[i], 1e-6f);
    EXPECT_NEAR(back.emission[i], light.emission[i], 1e-4f);
  }
  // A red wall without emission takes its colour from the reflectance.
  const MaterialControls red = to_controls({Vec3(0.63f, 0.065f, 0.05f), Vec3(0.0f)});
  EXPECT_EQ(red.colour.x, 1.0f);
  EXPECT_NEAR(red.reflectivity, 0.63f, 1e-6f);
  EXPECT_EQ(red.emission, 0.0f);
  EXPECT_EQ(to_controls({}), MaterialControls{});
  EXPECT_TRUE(controls_error(MaterialControls{Vec3(0.5f), 0.5f, 3.0f}) == std::nullopt);
  EXPECT_TRUE(controls_error(MaterialControls{Vec3(0.5f), 1.5f, 3.0f}).has_value());
}

}  // namespace
}  // namespace rad
