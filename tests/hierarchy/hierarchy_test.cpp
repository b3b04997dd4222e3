// The object hierarchy built from a parsed description: depth-first triangle ranges, boxes,
// normals and areas, degenerate triangles, materials.
#include "hierarchy/hierarchy.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "hierarchy/auto_hierarchy.h"
#include "scene/description_writer.h"
#include "scene/parser.h"
#include "scenegen/scenegen.h"

namespace rad {
namespace {

Hierarchy build(const std::string& text) {
  return build_hierarchy(parse_scene_text(text, "scene.des"));
}

const char* kNested = R"("nested"
Object "room" Assembly {
  Object "floor" Pure { Reflectivity 0.5 Color <1 0.5 0.2> Emission 0
    Data { <0 0 0> <0 0 4> <4 0 0>   <4 0 0> <0 0 4> <4 0 4> } }
  Object "table" Composite {
    Object "top" Pure { Reflectivity 0.8 Color <1 1 1> Emission 0
      Data { <1 1 1> <1 1 2> <2 1 1> } }
    Object "leg" Pure { Reflectivity 0.8 Color <1 1 1> Emission 0
      Data { <1 0 1> <1 1 1> <1.1 0 1> } }
  }
}
Object "lamp" Pure { Reflectivity 0 Color <1 0.9 0.8> Emission 10
  Data { <1 3 1> <2 3 1> <1 3 2> } }
)";

TEST(Hierarchy, KeepsObjectsAndKindsInDepthFirstOrder) {
  Hierarchy h = build(kNested);
  ASSERT_EQ(h.objects.size(), 6u);
  EXPECT_EQ(h.scene_name, "nested");
  EXPECT_EQ(h.source_path, "scene.des");
  EXPECT_EQ(h.roots, (std::vector<int32_t>{0, 5}));
  EXPECT_EQ(h.objects[0].kind, ObjectKind::Assembly);
  EXPECT_EQ(h.objects[0].children, (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(h.objects[2].kind, ObjectKind::Composite);
  EXPECT_EQ(h.objects[2].children, (std::vector<int32_t>{3, 4}));
  EXPECT_EQ(h.objects[3].parent, 2);
  EXPECT_EQ(h.objects[2].parent, 0);
  EXPECT_EQ(h.objects[0].parent, -1);
  EXPECT_EQ(h.objects[5].name, "lamp");
  EXPECT_EQ(h.objects[5].loc.line, 12);
}

TEST(Hierarchy, GivesEverySubtreeAContiguousTriangleRange) {
  Hierarchy h = build(kNested);
  ASSERT_EQ(h.triangles.size(), 5u);
  auto range = [&](int i) {
    return std::pair(h.objects[i].first_triangle, h.objects[i].triangle_count);
  };
  EXPECT_EQ(range(0), std::pair(0u, 4u));  // room
  EXPECT_EQ(range(1), std::pair(0u, 2u));  // floor
  EXPECT_EQ(range(2), std::pair(2u, 2u));  // table
  EXPECT_EQ(range(3), std::pair(2u, 1u));  // top
  EXPECT_EQ(range(4), std::pair(3u, 1u));  // leg
  EXPECT_EQ(range(5), std::pair(4u, 1u));  // lamp
  for (size_t o = 0; o < h.objects.size(); ++o) {
    const SceneObject& obj = h.objects[o];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      // The owning Pure is this object or below it.
      int32_t owner = h.triangles.object[t];
      while (owner != -1 && owner != static_cast<int32_t>(o)) owner = h.objects[owner].parent;
      EXPECT_EQ(owner, static_cast<int32_t>(o)) << "triangle " << t << " object " << o;
    }
  }
}

TEST(Hierarchy, ComputesBoxesOfEveryObjectAndTheScene) {
  Hierarchy h = build(kNested);
  EXPECT_EQ(h.objects[1].box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(h.objects[1].box.hi, Vec3(4, 0, 4));
  EXPECT_EQ(h.objects[2].box.lo, Vec3(1, 0, 1));
  EXPECT_EQ(h.objects[2].box.hi, Vec3(2, 1, 2));
  EXPECT_EQ(h.objects[0].box.hi, Vec3(4, 1, 4));
  EXPECT_EQ(h.bounds.lo, Vec3(0, 0, 0));
  EXPECT_EQ(h.bounds.hi, Vec3(4, 3, 4));
}

TEST(Hierarchy, ComputesUnitNormalsByTheRightHandRuleAndAreas) {
  Hierarchy h = build(kNested);
  // floor: (b-a)x(c-a) = (0,0,4)x(4,0,0) = (0,16,0): up, area 8.
  EXPECT_EQ(h.triangles.normal[0], Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(h.triangles.area[0], 8.0f);
  EXPECT_EQ(h.triangles.normal[1], Vec3(0, 1, 0));
  // lamp: (1,0,0)x(0,0,1) = (0,-1,0): down, area 0.5.
  EXPECT_EQ(h.triangles.normal[4], Vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(h.triangles.area[4], 0.5f);
  EXPECT_EQ(h.triangles.corners[4][1], Vec3(2, 3, 1));
  EXPECT_EQ(h.triangles.object[4], 5);
}

TEST(Hierarchy, CarriesMaterialProductsToPures) {
  Hierarchy h = build(kNested);
  EXPECT_FLOAT_EQ(h.objects[1].material.reflectance.g, 0.25f);
  EXPECT_FLOAT_EQ(h.objects[1].material.reflectance.b, 0.1f);
  EXPECT_FLOAT_EQ(h.objects[5].material.emission.r, 10.0f);
  EXPECT_FLOAT_EQ(h.objects[5].material.emission.b, 8.0f);
  EXPECT_EQ(h.objects[5].material.reflectance, Vec3(0.0f));
}

TEST(Hierarchy, DropsAndCountsDegenerateTriangles) {
  Hierarchy h = build(R"("d" Object "w" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data {
      <0 0 0> <1 0 0> <2 0 0>
      <0 0 0> <1 0 0> <0 1 0>
      <5 5 5> <5 5 5> <5 5 5> } })");
  EXPECT_EQ(h.triangles.size(), 1u);
  EXPECT_EQ(h.dropped_degenerate, 2u);
  EXPECT_EQ(h.objects[0].triangle_count, 1u);
  EXPECT_EQ(h.objects[0].box.hi, Vec3(1, 1, 0));  // dropped corners do not grow the box
}

TEST(Hierarchy, RejectsPureWhoseTrianglesAreAllDegenerate) {
  try {
    build(
        "\"d\"\nObject \"w\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data {"
        " <0 0 0> <1 0 0> <2 0 0> } }");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 2);
    EXPECT_EQ(e.loc().column, 1);
    EXPECT_NE(e.message().find("no triangles of non-zero area"), std::string::npos) << e.what();
  }
}

TEST(Hierarchy, SummarizesKindsTrianglesEmittersAndBounds) {
  std::string s = summarize(build(kNested));
  EXPECT_NE(s.find("1 Assemblies, 1 Composites, 4 Pures"), std::string::npos) << s;
  EXPECT_NE(s.find("Triangles: 5"), std::string::npos) << s;
  EXPECT_NE(s.find("Emitters: 1 Pures, 1 triangles"), std::string::npos) << s;
}

const char* kFlagged = R"("flags"
Object "house" Assembly Lights { "lamp" } {
  Object "room" Assembly CastsShadows No Lights { "hall" "lamp" } {
    Object "floor" Pure ReceivesShadows No { Reflectivity 0.5 Color <1 1 1> Emission 0
      Data { <0 0 0> <0 0 4> <4 0 0> } }
    Object "glass" Pure CastsShadows Yes { Reflectivity 0.5 Color <1 1 1> Emission 0
      Data { <0 0 0> <0 1 4> <4 0 0> } }
  }
  Object "wall" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0
    Data { <0 0 0> <0 2 4> <4 0 0> } }
}
Object "hall" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data { <0 0 0> <0 3 4> <4 0 0> } }
Object "lamp" Pure { Reflectivity 0 Color <1 1 1> Emission 5 Data { <0 0 0> <0 4 4> <4 0 0> } }
Object "lamp" Pure { Reflectivity 0 Color <1 1 1> Emission 5 Data { <0 0 0> <0 5 4> <4 0 0> } }
)";

TEST(Hierarchy, ObjectFlagsHoldForEverythingBelowUnlessSetAgain) {
  Hierarchy h = build(kFlagged);
  // house, room, floor, glass, wall, hall, lamp, lamp
  ASSERT_EQ(h.objects.size(), 8u);
  EXPECT_FALSE(h.objects[2].casts_shadows);  // floor: from room
  EXPECT_FALSE(h.objects[2].receives_shadows);
  EXPECT_TRUE(h.objects[3].casts_shadows);  // glass sets it again
  EXPECT_TRUE(h.objects[3].receives_shadows);
  EXPECT_TRUE(h.objects[4].casts_shadows);  // wall: house sets nothing
  EXPECT_EQ(h.objects[2].influence, 1);     // the nearest list: room's
  EXPECT_EQ(h.objects[4].influence, 0);     // house's
  EXPECT_EQ(h.objects[5].influence, -1);    // hall lights everything
}

TEST(Hierarchy, ALightsListReachesItselfAndEveryObjectOfEachName) {
  Hierarchy h = build(kFlagged);
  // Triangles: floor 0, glass 1, wall 2, hall 3, lamps 4 and 5.
  const std::vector<TriangleRange>& room = h.objects[1].lit;
  ASSERT_EQ(room.size(), 2u);  // room [0, 2) and hall + both lamps [3, 6), merged
  EXPECT_EQ(room[0].first, 0u);
  EXPECT_EQ(room[0].count, 2u);
  EXPECT_EQ(room[1].first, 3u);
  EXPECT_EQ(room[1].count, 3u);
  const bool expected[6] = {true, true, false, true, true, true};
  for (uint32_t t = 0; t < 6; ++t) EXPECT_EQ(influence_reaches(h, 1, t), expected[t]) << t;
  for (uint32_t t = 0; t < 6; ++t) EXPECT_EQ(influence_reaches(h, 0, t), t != 3) << t;
  for (uint32_t t = 0; t < 6; ++t) EXPECT_TRUE(influence_reaches(h, -1, t));
}

TEST(Hierarchy, RejectsALightsListNamingNoObject) {
  try {
    build(R"("s"
Object "a" Pure Lights { "nobody" } { Reflectivity 0 Color <1 1 1> Emission 1
  Data { <0 0 0> <0 1 0> <1 0 0> } })");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 2);
    EXPECT_EQ(e.loc().column, 26);
    EXPECT_NE(std::string(e.what()).find("\"a\" lights \"nobody\", but no object has that name"),
              std::string::npos)
        << e.what();
  }
}

const char* kPlaced = R"("placed"
Object "leg" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data { <0 0 0> <1 0 0> <0 1 0> } }
Object "chair" Composite Translate <10 0 0> {
  Object "seat" Pure Scale 2 { Reflectivity 0.5 Color <1 1 1> Emission 0
    Data { <0 0 0> <1 0 0> <0 1 0> } }
  Object "leg 2" Copy "leg" Translate <0 0 5>
}
Object "chair 2" Copy "chair" Rotate <0 0 1> 90
Object "mirror" Copy "leg" Scale <-1 1 1>
)";

TEST(Hierarchy, TransformsComposeDownTheTreeInTheOrderWritten) {
  Hierarchy h = build(kPlaced);
  // leg, chair, seat, leg 2, chair 2, seat, leg 2, mirror
  ASSERT_EQ(h.objects.size(), 8u);
  ASSERT_EQ(h.triangles.size(), 6u);
  auto near = [](Vec3 a, Vec3 b) { return glm::length(a - b) < 1e-5f; };
  // seat: scaled by 2, then moved with its chair.
  EXPECT_TRUE(near(h.triangles.corners[1][1], Vec3(12, 0, 0)));
  // leg 2 in the chair: the leg moved by its own translation, then by the chair's.
  EXPECT_TRUE(near(h.triangles.corners[2][2], Vec3(10, 1, 5)));
  // chair 2: the whole chair turned 90 degrees about z, after the chair's own placement.
  EXPECT_EQ(h.objects[4].name, "chair 2");
  EXPECT_EQ(h.objects[4].kind, ObjectKind::Composite);
  EXPECT_EQ(h.objects[5].name, "seat");
  EXPECT_TRUE(near(h.triangles.corners[3][1], Vec3(0, 12, 0)));
  EXPECT_TRUE(near(h.triangles.corners[4][2], Vec3(-1, 10, 5)));
  EXPECT_TRUE(near(h.triangles.normal[3], Vec3(0, 0, 1)));
}

TEST(Hierarchy, AMirroringCopyKeepsEveryTrianglesFront) {
  Hierarchy h = build(kPlaced);
  const auto& t = h.triangles.corners[5];
  // Mirrored in x, the leg's corners would turn its front to -z; swapped, it still faces +z.
  EXPECT_EQ(h.objects[7].name, "mirror");
  EXPECT_NEAR(h.triangles.normal[5].z, 1.0f, 1e-6f);
  EXPECT_NEAR(std::min({t[0].x, t[1].x, t[2].x}), -1.0f, 1e-6f);
}

TEST(Hierarchy, CopiesThatMultiplyBeyondTheLimitsAreRefused) {
  std::string text =
      "\"s\"\nObject \"c0\" Pure { Reflectivity 0 Color <1 1 1> Emission 1 Data "
      "{ <0 0 0> <1 0 0> <0 1 0> } }\n";
  for (int i = 1; i <= 30; ++i) {  // each level doubles: 2^30 triangles
    text += "Object \"c" + std::to_string(i) + "\" Assembly { Object \"a\" Copy \"c" +
            std::to_string(i - 1) + "\" Object \"b\" Copy \"c" + std::to_string(i - 1) +
            "\" Translate <1 0 0> }\n";
  }
  try {
    build_hierarchy(parse_scene_text(text, "scene.des"), BuildLimits{1000, 100000, 256});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1000 triangles"), std::string::npos)
        << e.what();
  }
}

TEST(Hierarchy, CopiesTransformsAndFlagsSurviveWritingTheDescriptionBack) {
  // rad-tessellate and rad-gen write descriptions back: the copies stay copies, placed alike.
  const SceneDescription d = parse_scene_text(kPlaced, "scene.des");
  std::ostringstream text;
  write_description(d, text);
  const SceneDescription again = parse_scene_text(text.str(), "again.des");
  EXPECT_EQ(again.objects[4].copy_of, 1) << text.str();
  const Hierarchy a = build_hierarchy(d), b = build_hierarchy(again);
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t t = 0; t < a.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(glm::length(a.triangles.corners[t][size_t(k)] - b.triangles.corners[t][size_t(k)]),
                1e-5f)
          << t;
    }
  }
}

// A lamp fixture (a shade and a spot light) placed, copied rotated and scaled; a group of lights
// alone; a copy of a light.
const char* kLit = R"("lit"
Object "floor" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0
  Data { <-9 0 -9> <-9 0 9> <9 0 9> } }
Object "fixture" Assembly Translate <1 0 0> {
  Object "shade" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0
    Data { <0 2 0> <0 2 1> <1 2 0> } }
  Object "spot" Light { Type Spot Position <0 2 0> Direction <0 -1 0> Intensity 500 Cone 20 30 }
}
Object "fixture 2" Copy "fixture" Rotate <0 0 1> 90 Scale 2
Object "lamps" Assembly {
  Object "a" Light { Type Point Position <0 3 0> Intensity 10 Group "room" }
  Object "sun" Light Rotate <0 0 1> 90 {
    Type Directional Direction <0 -1 0> Intensity 1000 AngularDiameter 1 }
}
Object "b" Copy "a" Translate <0 0 4>
)";

TEST(HierarchyLights, LightsArePlacedLikeObjectsAndCopiesAreFlattened) {
  const Hierarchy h = build(kLit);
  // Objects: floor, fixture, shade, fixture 2, shade; no object for a light or the lights' group.
  ASSERT_EQ(h.objects.size(), 5u);
  EXPECT_EQ(h.roots, (std::vector<int32_t>{0, 1, 3}));
  EXPECT_EQ(h.objects[1].children, (std::vector<int32_t>{2}));
  ASSERT_EQ(h.lights.size(), 5u);
  auto near = [](Vec3 a, Vec3 b) { return glm::length(a - b) < 1e-5f; };
  const Light& spot = h.lights[0];
  EXPECT_EQ(spot.name, "spot");
  EXPECT_TRUE(near(spot.position, Vec3(1, 2, 0)));
  EXPECT_TRUE(near(spot.direction, Vec3(0, -1, 0)));
  // The copy: translated, then turned 90 degrees about z, then scaled 2. A scale moves a light;
  // it neither brightens it nor widens its cone.
  const Light& spot2 = h.lights[1];
  EXPECT_EQ(spot2.name, "spot");  // inside a copy, as its objects are: named as in the original
  EXPECT_EQ(spot2.loc.line, 7);
  EXPECT_TRUE(near(spot2.position, Vec3(-4, 2, 0))) << spot2.position.x << " " << spot2.position.y;
  EXPECT_TRUE(near(spot2.direction, Vec3(1, 0, 0)));
  EXPECT_EQ(spot2.intensity, 500.0f);
  EXPECT_EQ(spot2.outer_cone, spot.outer_cone);
  EXPECT_NEAR(glm::dot(spot2.photometric_up, spot2.direction), 0.0f, 1e-6f);
  EXPECT_EQ(h.lights[2].name, "a");
  EXPECT_EQ(h.lights[2].group, "room");
  EXPECT_TRUE(near(h.lights[3].direction, Vec3(1, 0, 0)));  // the sun, turned
  EXPECT_EQ(h.lights[4].name, "b");
  EXPECT_TRUE(near(h.lights[4].position, Vec3(0, 3, 4)));
  EXPECT_EQ(h.lights[4].group, "room");
  EXPECT_NE(summarize(h).find("Lights: 5 (2 point, 2 spot, 1 directional; 0 with IES"),
            std::string::npos)
      << summarize(h);
}

TEST(HierarchyLights, RegroupingAndWritingTheDescriptionBackKeepTheLights) {
  const SceneDescription d = parse_scene_text(kLit, "scene.des");
  const Hierarchy h = build_hierarchy(d);
  std::ostringstream text;
  write_description(d, text);
  const Hierarchy again = build_hierarchy(parse_scene_text(text.str(), "again.des"));
  for (const HierarchyMode mode : {HierarchyMode::Automatic, HierarchyMode::Flat}) {
    const Hierarchy r = regrouped_hierarchy(h, mode);
    ASSERT_EQ(r.lights.size(), h.lights.size());
    EXPECT_EQ(build_hierarchy(regroup(d, mode)).lights.size(), h.lights.size());
  }
  ASSERT_EQ(again.lights.size(), h.lights.size()) << text.str();
  for (size_t i = 0; i < h.lights.size(); ++i) {
    const Light &a = h.lights[i], &b = again.lights[i];
    EXPECT_EQ(a.kind, b.kind) << i;
    EXPECT_LT(glm::length(a.position - b.position), 1e-5f) << i;
    EXPECT_LT(glm::length(a.direction - b.direction), 1e-5f) << i;
    EXPECT_NEAR(a.outer_cone, b.outer_cone, 1e-6f) << i;
    EXPECT_NEAR(a.angular_diameter, b.angular_diameter, 1e-6f) << i;
    EXPECT_EQ(a.intensity, b.intensity) << i;
    EXPECT_EQ(a.group, b.group) << i;
  }
}

TEST(HierarchyLights, ASceneOfLightsAloneOrALightTooFarIsRefused) {
  try {
    build("\"s\"\nObject \"a\" Light { Type Point Position <0 1 0> Intensity 1 }\n");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no surfaces"), std::string::npos) << e.what();
  }
  // A light beyond the coordinates rad computes with, once placed.
  try {
    build(std::string("\"s\"\n") +
          "Object \"f\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0 Data { <0 0 0> <1 0 0> "
          "<0 1 0> } }\n"
          "Object \"a\" Light Translate <2e8 0 0> { Type Point Position <0 1 0> Intensity 1 }\n");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 3);
    EXPECT_NE(std::string(e.what()).find("too far"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rad
