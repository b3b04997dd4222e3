// The description grammar of design §2: every construct, materials, locations, and every error
// with its exact line and column.
#include "scene/parser.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/mat4x4.hpp>
#include <string>

#include "scene_texts.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// A Pure with one triangle, for building larger scenes in tests.
std::string pure(const std::string& name, const std::string& body = "") {
  return "Object \"" + name + "\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 " +
         (body.empty() ? "Data { <0 0 0> <1 0 0> <0 1 0> }" : body) + " }\n";
}

void expect_error(std::string_view text, int line, int column, const std::string& substring) {
  Error e = testing::parse_error(text);
  EXPECT_EQ(e.loc().file, "scene.des");
  EXPECT_EQ(e.loc().line, line) << e.what();
  EXPECT_EQ(e.loc().column, column) << e.what();
  EXPECT_NE(e.message().find(substring), std::string::npos) << e.what();
}

// A fresh folder under the build tree for OFF files, removed at the end of the test.
class ParserFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(RAD_BINARY_DIR) / "test_tmp" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "off");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

const char* kTriangleOff = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST(Parser, ReadsSceneNameAndOnePure) {
  SceneDescription s = parse_scene_text("\"My scene\"\n" + pure("wall"), "scene.des");
  EXPECT_EQ(s.name, "My scene");
  EXPECT_EQ(s.path, "scene.des");
  ASSERT_EQ(s.objects.size(), 1u);
  ASSERT_EQ(s.roots.size(), 1u);
  const ObjectDescription& o = s.objects[0];
  EXPECT_EQ(o.name, "wall");
  EXPECT_EQ(o.kind, ObjectKind::Pure);
  ASSERT_EQ(o.triangles.size(), 1u);
  EXPECT_EQ(o.triangles[0][0], Vec3(0, 0, 0));
  EXPECT_EQ(o.triangles[0][1], Vec3(1, 0, 0));
  EXPECT_EQ(o.triangles[0][2], Vec3(0, 1, 0));
}

TEST(Parser, KeepsSpacesInStrings) {
  SceneDescription s = parse_scene_text("\"  a  b \"" + pure("left wall (red)"), "scene.des");
  EXPECT_EQ(s.name, "  a  b ");
  EXPECT_EQ(s.objects[0].name, "left wall (red)");
}

TEST(Parser, ReadsAssemblyOfCompositesAndPuresDepthFirst) {
  std::string text =
      "\"s\"\n"
      "Object \"room\" Assembly {\n" +
      pure("floor") + "  Object \"table\" Composite {\n" + pure("top") + pure("leg") +
      "  }\n"
      "  Object \"inner\" Assembly { " +
      pure("lamp") + " }\n" + "}\n" + pure("outside");
  SceneDescription s = parse_scene_text(text, "scene.des");
  ASSERT_EQ(s.objects.size(), 8u);
  ASSERT_EQ(s.roots, (std::vector<int32_t>{0, 7}));
  EXPECT_EQ(s.objects[0].kind, ObjectKind::Assembly);
  EXPECT_EQ(s.objects[0].children, (std::vector<int32_t>{1, 2, 5}));
  EXPECT_EQ(s.objects[2].kind, ObjectKind::Composite);
  EXPECT_EQ(s.objects[2].name, "table");
  EXPECT_EQ(s.objects[2].children, (std::vector<int32_t>{3, 4}));
  EXPECT_EQ(s.objects[5].children, (std::vector<int32_t>{6}));
  EXPECT_EQ(s.objects[6].name, "lamp");
  EXPECT_EQ(s.objects[7].name, "outside");
  EXPECT_TRUE(s.objects[1].children.empty());
}

TEST(Parser, AllowsDuplicateObjectNames) {
  SceneDescription s = parse_scene_text("\"s\"" + pure("a") + pure("a"), "scene.des");
  EXPECT_EQ(s.objects.size(), 2u);
}

TEST(Parser, RecordsWhereEachObjectWasWritten) {
  SceneDescription s = parse_scene_text(
      "\"s\"\n  Object \"a\" Assembly {\n\tObject \"b\" "
      "Pure { Reflectivity 0 Color <0 0 0> Emission 0 Data "
      "{ <0 0 0> <1 0 0> <0 1 0> } } }",
      "scene.des");
  EXPECT_EQ(s.objects[0].loc.line, 2);
  EXPECT_EQ(s.objects[0].loc.column, 3);
  EXPECT_EQ(s.objects[1].loc.line, 3);
  EXPECT_EQ(s.objects[1].loc.column, 2);
  EXPECT_EQ(s.objects[1].loc.file, "scene.des");
}

TEST(Parser, MultipliesReflectivityAndEmissionByColor) {
  SceneDescription s = parse_scene_text(
      "\"s\" Object \"lamp\" Pure { Reflectivity 0.5 Color <1 0.5 0.25> Emission 4 "
      "Data { <0 0 0> <1 0 0> <0 1 0> } }",
      "scene.des");
  const Material& m = s.objects[0].material;
  EXPECT_FLOAT_EQ(m.reflectance.r, 0.5f);
  EXPECT_FLOAT_EQ(m.reflectance.g, 0.25f);
  EXPECT_FLOAT_EQ(m.reflectance.b, 0.125f);
  EXPECT_FLOAT_EQ(m.emission.r, 4.0f);
  EXPECT_FLOAT_EQ(m.emission.g, 2.0f);
  EXPECT_FLOAT_EQ(m.emission.b, 1.0f);
}

TEST(Parser, AcceptsColorAboveOneWhenTheProductIsAtMostOne) {
  SceneDescription s = parse_scene_text(
      "\"s\" Object \"w\" Pure { Reflectivity 0.25 Color <4 2 0> Emission 0 "
      "Data { <0 0 0> <1 0 0> <0 1 0> } }",
      "scene.des");
  EXPECT_FLOAT_EQ(s.objects[0].material.reflectance.r, 1.0f);
}

TEST(Parser, ReadsSeveralTrianglesAndLocatesEachAtItsFirstCorner) {
  SceneDescription s = parse_scene_text(
      "\"s\"\nObject \"w\" Pure { Reflectivity 0 Color <0 0 0> Emission 0 Data {\n"
      "  <0 0 0> <1 0 0> <0 1 0>   <0 0 1>\n"
      "<1 0 1>\n"
      "<0 1 1>\n"
      "} }",
      "scene.des");
  const ObjectDescription& o = s.objects[0];
  ASSERT_EQ(o.triangles.size(), 2u);
  EXPECT_EQ(o.triangles[1][2], Vec3(0, 1, 1));
  ASSERT_EQ(o.triangle_locs.size(), 2u);
  EXPECT_EQ(o.triangle_locs[0].line, 3);
  EXPECT_EQ(o.triangle_locs[0].column, 3);
  EXPECT_EQ(o.triangle_locs[1].line, 3);
  EXPECT_EQ(o.triangle_locs[1].column, 29);
  EXPECT_EQ(o.triangle_locs[1].file, "scene.des");
}

TEST(Parser, ReadsNumbersInEveryCLikeForm) {
  SceneDescription s = parse_scene_text(
      "\"s\" Object \"w\" Pure { Reflectivity .5 Color <+1 1. 1e-1> Emission 2E0 "
      "Data { <-0.5 +3 1e-3> <2. .5 -1> <0 1e2 -.25> } }",
      "scene.des");
  const ObjectDescription& o = s.objects[0];
  EXPECT_FLOAT_EQ(o.material.reflectance.b, 0.05f);
  EXPECT_FLOAT_EQ(o.material.emission.r, 2.0f);
  EXPECT_EQ(o.triangles[0][0], Vec3(-0.5f, 3.0f, 1e-3f));
  EXPECT_EQ(o.triangles[0][1], Vec3(2.0f, 0.5f, -1.0f));
  EXPECT_EQ(o.triangles[0][2], Vec3(0.0f, 100.0f, -0.25f));
}

TEST(Parser, AcceptsAnyWhitespaceCommentsAndCrLf) {
  SceneDescription s = parse_scene_text(
      "; header comment\r\n\"s\"\t; the name\r\n\r\nObject\t\"w\"Pure{Reflectivity 0.5\r\n"
      "Color<1 1 1>Emission 0 ; comment { \"\r\nData{<0 0 0><1 0 0><0 1 0>}}\r\n",
      "scene.des");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].triangles.size(), 1u);
  EXPECT_EQ(s.objects[0].triangle_locs[0].line, 6);
  EXPECT_EQ(s.objects[0].triangle_locs[0].column, 6);
}

TEST_F(ParserFiles, ReadsFileRelativeToTheDescription) {
  write("off/tri.off", kTriangleOff);
  write("scene.des", "\"s\"\n" + pure("w", "File off/tri.off"));
  SceneDescription s = parse_scene_file(path("scene.des"));
  ASSERT_EQ(s.objects[0].triangles.size(), 1u);
  EXPECT_EQ(s.objects[0].triangles[0][1], Vec3(1, 0, 0));
  EXPECT_EQ(s.objects[0].triangle_locs[0].file, path("off/tri.off"));
  EXPECT_EQ(s.objects[0].triangle_locs[0].line, 6);
}

TEST_F(ParserFiles, ReadsQuotedFileNameWithSpaces) {
  write("off/a triangle.off", kTriangleOff);
  SceneDescription s =
      parse_scene_text("\"s\"" + pure("w", "File \"off/a triangle.off\""), path("scene.des"));
  EXPECT_EQ(s.objects[0].triangles.size(), 1u);
}

TEST_F(ParserFiles, ReadsFileNameFollowedDirectlyByBrace) {
  write("tri.geo", kTriangleOff);
  SceneDescription s = parse_scene_text(
      "\"s\" Object \"w\" Pure { Reflectivity 0 Color <0 0 0> Emission 0 File tri.geo}",
      path("scene.des"));
  EXPECT_EQ(s.objects[0].triangles.size(), 1u);
}

TEST_F(ParserFiles, ReportsMissingFileAtItsName) {
  Error e = testing::parse_error("\"s\"\n" + pure("w", "File  off/none.off"), path("scene.des"));
  EXPECT_EQ(e.loc().file, path("scene.des"));
  EXPECT_EQ(e.loc().line, 2);
  EXPECT_EQ(e.loc().column, 67);
  EXPECT_NE(e.message().find("cannot open"), std::string::npos) << e.what();
}

TEST_F(ParserFiles, ReportsFolderGivenAsFile) {
  Error e = testing::parse_error("\"s\"\n" + pure("w", "File off"), path("scene.des"));
  EXPECT_EQ(e.loc().column, 66);
  EXPECT_NE(e.message().find("not a regular file"), std::string::npos) << e.what();
}

TEST_F(ParserFiles, ReportsErrorsInsideTheOffFileAtTheOffFile) {
  write("off/bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  Error e = testing::parse_error("\"s\"\n" + pure("w", "File off/bad.off"), path("scene.des"));
  EXPECT_EQ(e.loc().file, path("off/bad.off"));
  EXPECT_EQ(e.loc().line, 6);
  EXPECT_EQ(e.loc().column, 7);
  EXPECT_NE(e.message().find("out of range"), std::string::npos) << e.what();
}

TEST_F(ParserFiles, ReportsMissingDescriptionFile) {
  try {
    parse_scene_file(path("none.des"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().file, path("none.des"));
    EXPECT_EQ(e.loc().line, 0);
    EXPECT_NE(e.message().find("cannot open"), std::string::npos);
  }
}

TEST(Parser, ReadsObjectFlagsAndLightsLists) {
  SceneDescription d = parse_scene_text(
      "\"s\"\nObject \"room\" Assembly Lights { \"hall\" \"room 2\" } CastsShadows Yes {\n" +
          pure("lamp") + "}\nObject \"glass\" Pure ReceivesShadows No CastsShadows No " +
          pure("x").substr(pure("x").find('{')),
      "scene.des");
  ASSERT_EQ(d.objects.size(), 3u);
  const ObjectFlags& room = d.objects[0].flags;
  EXPECT_TRUE(room.has_lights);
  ASSERT_EQ(room.lights.size(), 2u);
  EXPECT_EQ(room.lights[1].name, "room 2");
  EXPECT_EQ(room.lights[1].loc.line, 2);
  EXPECT_EQ(room.lights[1].loc.column, 40);
  EXPECT_EQ(room.casts_shadows, std::optional<bool>(true));
  EXPECT_FALSE(room.receives_shadows.has_value());
  const ObjectFlags& lamp = d.objects[1].flags;
  EXPECT_FALSE(lamp.has_lights || lamp.casts_shadows || lamp.receives_shadows);
  EXPECT_EQ(d.objects[2].flags.casts_shadows, std::optional<bool>(false));
  EXPECT_EQ(d.objects[2].flags.receives_shadows, std::optional<bool>(false));
}

TEST(Parser, AcceptsAnEmptyLightsList) {
  SceneDescription d = parse_scene_text(
      "\"s\" Object \"a\" Pure Lights { } " + pure("x").substr(pure("x").find('{')), "scene.des");
  EXPECT_TRUE(d.objects[0].flags.has_lights);
  EXPECT_TRUE(d.objects[0].flags.lights.empty());
}

TEST(Parser, ReportsBadObjectFlags) {
  expect_error("\"s\"\nObject \"w\" Pure CastsShadows Maybe {", 2, 30,
               "expected 'Yes' or 'No' after 'CastsShadows'");
  expect_error("\"s\"\nObject \"w\" Pure CastsShadows No CastsShadows Yes {", 2, 33,
               "'CastsShadows' given twice");
  expect_error("\"s\"\nObject \"w\" Pure Lights { lamp } {", 2, 26,
               "expected an object's name (a quoted string) or '}' but found 'lamp'");
  expect_error("\"s\"\nObject \"w\" Pure Lights \"lamp\" {", 2, 24, "expected '{' after 'Lights'");
  expect_error("\"s\"\nObject \"w\" Pure receivesShadows No {", 2, 17,
               "keywords are case-sensitive: 'ReceivesShadows'");
}

TEST(Parser, ACopyNamesAnEarlierObjectAndKeepsOnlyItsPlacement) {
  SceneDescription d = parse_scene_text(
      "\"s\"\n" + pure("lamp") + "Object \"lamp 2\" Copy \"lamp\" Translate <1 2 3> Scale 2\n" +
          "Object \"w\" Pure Rotate <0 1 0> 90 " + pure("x").substr(pure("x").find('{')),
      "scene.des");
  ASSERT_EQ(d.objects.size(), 3u);
  const ObjectDescription& copy = d.objects[1];
  EXPECT_EQ(copy.copy_of, 0);
  EXPECT_EQ(copy.kind, ObjectKind::Pure);
  EXPECT_TRUE(copy.triangles.empty());
  // Written order: translate, then scale (of the translated object).
  ASSERT_EQ(copy.transforms.size(), 2u);
  EXPECT_EQ(copy.transforms[1].kind, Transform::Kind::Scale);
  EXPECT_EQ(copy.transforms[1].v, DVec3(2.0));
  const glm::dvec4 p = transform_matrix(copy.transforms) * glm::dvec4(0, 0, 0, 1);
  EXPECT_EQ(glm::dvec3(p), glm::dvec3(2, 4, 6));
  const glm::dvec4 q = transform_matrix(d.objects[2].transforms) * glm::dvec4(1, 0, 0, 1);
  EXPECT_NEAR(q.z, -1.0, 1e-12);
}

TEST(Parser, ReportsBadCopiesAndTransforms) {
  expect_error("\"s\"\nObject \"a\" Copy \"b\"", 2, 17, "no object \"b\" is defined before");
  // An object still open cannot be copied into itself.
  expect_error("\"s\"\nObject \"a\" Assembly { Object \"b\" Copy \"a\" }", 2, 39,
               "no object \"a\" is defined before");
  expect_error("\"s\"\nObject \"w\" Pure Rotate <0 0 0> 30 {", 2, 25,
               "the rotation's axis is zero");
  expect_error("\"s\"\nObject \"w\" Pure Scale <1 0 1> {", 2, 26, "a scale factor of 0");
  expect_error("\"s\"\nObject \"w\" Pure Translate 1 {", 2, 27,
               "expected '<' starting the translation");
}

TEST(Parser, FormatsErrorsAsPathLineColumn) {
  Error e =
      testing::parse_error("\"s\"\nObject \"w\" Pure { Reflectivity 0.5 Color <1 1 1>\n  Object");
  EXPECT_STREQ(e.what(), "scene.des:3:3: error: expected 'Emission' but found 'Object'");
}

TEST(Parser, ReportsLineOfUnknownKeyword) {
  expect_error("\"s\"\nObject \"w\" Pure {\n  Reflectance 0.5", 3, 3,
               "unknown keyword 'Reflectance': expected 'Reflectivity'");
}

TEST(Parser, ReportsUnknownObjectKind) {
  expect_error("\"s\"\nObject \"w\" Mesh {", 2, 12,
               "unknown keyword 'Mesh': expected 'Assembly', 'Composite', 'Pure', 'Light', 'Copy' "
               "or 'Model'");
}

TEST(Parser, ReportsKeywordsAreCaseSensitive) {
  expect_error("\"s\"\nObject \"w\" pure {", 2, 12, "keywords are case-sensitive: 'Pure'");
  expect_error("\"s\" OBJECT", 1, 5, "unknown keyword 'OBJECT'");
}

TEST(Parser, ReportsMisplacedKeyword) {
  expect_error("\"s\"\n" + pure("a", "Data { <0 0 0> <1 0 0> <0 1 0> } Object"), 2, 94,
               "expected '}' closing the Pure but found 'Object'");
}

TEST(Parser, ReportsMissingSceneName) {
  expect_error("  " + pure("a"), 1, 3, "expected the scene's name");
}

TEST(Parser, ReportsMissingObjectName) {
  expect_error("\"s\" Object Pure", 1, 12,
               "expected the object's name (a quoted string) but found 'Pure'");
}

TEST(Parser, ReportsSceneWithoutObjects) {
  expect_error("\"s\" ; nothing\n", 2, 1, "unexpected end of file: expected 'Object'");
}

TEST(Parser, ReportsStrayTokenAfterTheLastObject) {
  expect_error("\"s\"" + pure("a") + "}", 2, 1, "expected 'Object' or end of file but found '}'");
}

TEST(Parser, ReportsUnexpectedEndOfFile) {
  expect_error("\"s\"\nObject \"a\" Assembly {\n" + pure("b"), 4, 1,
               "unexpected end of file: expected 'Object' or '}'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity", 1, 35,
               "unexpected end of file: expected the reflectivity");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0 Color <0 0 0> Emission 0 Data { <0 0", 1,
               74, "unexpected end of file: expected a number");
}

TEST(Parser, ReportsUnterminatedString) {
  expect_error("\"s\"\nObject \"wall Pure {\n", 2, 8, "unterminated string");
}

TEST(Parser, ReportsReflectanceAboveOneAtTheChannel) {
  expect_error("\"s\"\nObject \"w\" Pure { Reflectivity 0.8 Color <1 1 1.5> Emission 0", 2, 47,
               "reflectance 1.2 (Reflectivity 0.8 x Color 1.5) of the blue channel is outside "
               "[0, 1]");
  expect_error("\"s\"\nObject \"w\" Pure { Reflectivity 2 Color <1 0 0> Emission 0", 2, 41,
               "red channel");
}

TEST(Parser, ReportsNegativeReflectivity) {
  expect_error("\"s\"\nObject \"w\" Pure { Reflectivity -0.1 Color <1 1 1>", 2, 32,
               "negative reflectivity -0.1");
}

TEST(Parser, ReportsNegativeColor) {
  expect_error("\"s\"\nObject \"w\" Pure { Reflectivity 0.5 Color <1 -1 1>", 2, 45,
               "negative green colour component -1");
}

TEST(Parser, ReportsNegativeEmission) {
  expect_error("\"s\"\nObject \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission -3", 2, 59,
               "negative emission -3");
}

TEST(Parser, ReportsNonFiniteNumbers) {
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 1e999", 1, 36, "non-finite number '1e999'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <nan 1 1>", 1, 47,
               "non-finite number 'nan'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission inf", 1, 63,
               "non-finite number 'inf'");
  expect_error(
      "\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data { <0 0 -1e400> "
      "<1 0 0> <0 1 0> } }",
      1, 77, "non-finite number '-1e400'");
}

TEST(Parser, ReportsWordWhereNumberExpected) {
  expect_error("\"s\" Object \"w\" Pure { Reflectivity half", 1, 36,
               "expected the reflectivity (a number) but found 'half'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1, 1, 1>", 1, 47,
               "expected a number but found '1,'");
}

TEST(Parser, ReportsMissingVectorBrackets) {
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color 1 1 1", 1, 46,
               "expected '<' starting the colour but found '1'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1 1>", 1, 53,
               "expected '>' closing the colour but found '1'");
}

TEST(Parser, ReportsCompositeHoldingAnAssemblyAtItsKind) {
  expect_error("\"s\"\nObject \"c\" Composite {\n" + pure("a") + "  Object \"x\" Assembly {", 4, 14,
               "a Composite holds only Pures, but \"x\" is an Assembly");
}

TEST(Parser, ReportsCompositeHoldingACompositeAtItsKind) {
  expect_error("\"s\"\nObject \"c\" Composite { Object \"x\" Composite {", 2, 35,
               "a Composite holds only Pures, but \"x\" is a Composite");
}

TEST(Parser, ReportsCompositeHoldingSomethingOtherThanAnObject) {
  expect_error("\"s\"\nObject \"c\" Composite { Pure {", 2, 24,
               "expected 'Object' but found 'Pure'");
}

TEST(Parser, ReportsEmptyAssembly) {
  expect_error("\"s\"\nObject \"room\" Assembly {\n}", 3, 1,
               "empty Assembly \"room\": expected 'Object' but found '}'");
}

TEST(Parser, ReportsEmptyComposite) {
  expect_error("\"s\"\nObject \"t\" Composite { }", 2, 24,
               "empty Composite \"t\": expected 'Object' but found '}'");
}

TEST(Parser, ReportsEmptyData) {
  expect_error("\"s\"\n" + pure("w", "Data { }"), 2, 68,
               "empty Data in \"w\": expected '<' but found '}'");
}

TEST(Parser, ReportsDataWithCornerCountNotAMultipleOfThree) {
  expect_error("\"s\"\n" + pure("w", "Data { <0 0 0> <1 0 0> <0 1 0> <0 0 0> }"), 2, 100,
               "expected '<' but found '}': a triangle needs 3 corners, this one has 1");
  expect_error("\"s\"\n" + pure("w", "Data { <0 0 0> <1 0 0> }"), 2, 84, "this one has 2");
}

TEST(Parser, ReportsMissingGeometry) {
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 }", 1, 65,
               "expected 'File' or 'Data' but found '}'");
}

TEST(Parser, ReportsMissingFileName) {
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 File }", 1, 70,
               "expected a file name but found '}'");
  expect_error("\"s\" Object \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 File \"\" }", 1,
               70, "expected a file name");
}

}  // namespace
}  // namespace rad
