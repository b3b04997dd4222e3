// Light groups: which emitters form a group, and each group's light kept apart through the solve,
// adding up to the whole solve's (radiosity is linear in the emission).
#include "solver/light_groups.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>

#include "core/error.h"
#include "hierarchy/hierarchy.h"
#include "scene/parser.h"
#include "scene_builder.h"
#include "solver/edits.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

// Groups given by an object's flag reach its Pures and its Lights without a Group of their own;
// a light's own Group wins; a Copy's flag wins over its original's.
const char* kGrouped = R"("grouped"
Object "floor" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0
  Data { <-9 0 -9> <-9 0 9> <9 0 9> } }
Object "kitchen" Assembly Group "kitchen" {
  Object "panel" Pure { Reflectivity 0.5 Color <1 1 1> Emission 4
    Data { <0 2 0> <1 2 0> <0 2 1> } }
  Object "bulb" Light { Type Point Position <0 1 0> Intensity 10 }
  Object "night light" Light { Type Point Position <0 1 1> Intensity 1 Group "night" }
}
Object "porch" Copy "kitchen" Translate <5 0 0> Group "porch"
Object "lamp" Pure { Reflectivity 0.5 Color <1 1 1> Emission 2
  Data { <0 3 0> <1 3 0> <0 3 1> } }
Object "off" Light { Type Point Position <0 1 0> Intensity 0 Group "off" }
)";

TEST(LightGroups, AnObjectsGroupReachesWhatEmitsBelowItUnlessALightNamesItsOwn) {
  const Hierarchy h = build_hierarchy(parse_scene_text(kGrouped, "grouped.des"));
  // Emitting objects first (kitchen's panel, porch's panel, the lamp), then lights; a group
  // named by a light the scene leaves off ("off") is kept for an edit that turns it on.
  EXPECT_EQ(light_group_names(h),
            (std::vector<std::string>{"kitchen", "porch", "", "night", "off"}));
  ASSERT_EQ(h.lights.size(), 5u);
  EXPECT_EQ(h.lights[0].group, "kitchen");  // bulb: its Assembly's
  EXPECT_EQ(h.lights[1].group, "night");    // its own
  EXPECT_EQ(h.lights[2].group, "porch");    // the copy's bulb: the copy's flag
  EXPECT_EQ(h.lights[3].group, "night");
}

TEST(LightGroups, AGroupFlagOnALightOrTwiceOnAnObjectIsRefusedWithItsPlace) {
  try {
    parse_scene_text(
        "\"s\"\nObject \"l\" Light Group \"g\" { Type Point Position <0 1 0> "
        "Intensity 1 }\n",
        "s.des");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("s.des:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inside its braces"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_scene_text("\"s\"\nObject \"a\" Assembly Group \"g\" Group \"h\" {\n"
                                "Object \"p\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 1 "
                                "Data { <0 0 0> <1 0 0> <0 1 0> } } }\n",
                                "s.des"),
               Error);
}

// The Cornell box lit by its ceiling panel (group "panel") and a bluish point light (group
// "lamp"), scenes/cornell_box_groups.des, at default settings (the roulette on): every shot's
// gain is split between the groups by the same weights and rays, so at every vertex the groups
// add up to the whole solve's radiosity to float rounding; and each group is the light of its
// emitters alone, as a solve of the scene with the other group's emitters off finds it (within
// the two solves' convergence: the same total light to 1%).
TEST(LightGroups, TheGroupsAddUpToTheWholeSolveAndEachIsItsEmittersLight) {
  std::ifstream in(RAD_SOURCE_DIR "/scenes/cornell_box_groups.des");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Hierarchy h = build_hierarchy(parse_scene_text(text, "cornell_box_groups.des"));
  size_t panel = h.objects.size();
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].group == "panel") panel = i;
  }
  ASSERT_LT(panel, h.objects.size());
  ASSERT_EQ(h.lights.size(), 1u);
  EXPECT_EQ(h.lights[0].group, "lamp");
  ASSERT_EQ(light_group_names(h), (std::vector<std::string>{"panel", "lamp"}));

  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  ASSERT_EQ(s.solution.group_count, 2u);
  EXPECT_FALSE(s.options.overshoot);
  solve(s, *vis);

  double diff = 0.0, total = 0.0, worst = 0.0, lamp_light = 0.0;
  size_t panel_vertices = 0;
  for (size_t p = 0; p < s.solution.vertex_states.size(); ++p) {
    const bool on_panel = size_t(h.triangles.object[p]) == panel;
    const double area = h.triangles.area[p] / double(s.solution.vertex_states[p].size());
    for (uint32_t v = 0; v < s.solution.vertex_states[p].size(); ++v) {
      const Vec3 all = s.solution.radiosity(p, v);
      const Vec3 a = s.solution.group_radiosity(0, p, v), b = s.solution.group_radiosity(1, p, v);
      const double d = mean_component(glm::abs(all - a - b));
      diff += d;
      total += double(mean_component(all));
      worst = std::max(worst, d / (double(mean_component(all)) + 1e-3));
      lamp_light += area * double(mean_component(b));
      if (on_panel) {  // the panel emits in its own group only
        ++panel_vertices;
        const float e = mean_component(s.solution.emission(p, v));
        EXPECT_GE(mean_component(a), 0.999f * e);
        EXPECT_LT(mean_component(b), mean_component(all) - e + 0.01f * mean_component(all));
      }
    }
  }
  EXPECT_LT(diff / total, 1e-5) << "mean |whole - sum of groups| / mean whole";
  EXPECT_LT(worst, 1e-3) << "the worst vertex";
  EXPECT_GT(panel_vertices, 0u);

  // The lamp alone: the same scene with the panel dark.
  const std::string dark = std::regex_replace(text, std::regex("Emission [0-9.]+"), "Emission 0");
  ASSERT_NE(dark, text);
  const Hierarchy lamp_only = build_hierarchy(parse_scene_text(dark, "lamp_only.des"));
  const auto lamp_vis = make_visibility_backend(BackendKind::Embree, lamp_only);
  SolverState alone = make_solver_state(lamp_only, SolverOptions{});
  EXPECT_EQ(alone.solution.group_count, 0u);
  solve(alone, *lamp_vis);
  double alone_light = 0.0;
  for (size_t p = 0; p < alone.solution.vertex_states.size(); ++p) {
    const double area =
        lamp_only.triangles.area[p] / double(alone.solution.vertex_states[p].size());
    for (uint32_t v = 0; v < alone.solution.vertex_states[p].size(); ++v)
      alone_light += area * double(mean_component(alone.solution.radiosity(p, v)));
  }
  EXPECT_NEAR(lamp_light / alone_light, 1.0, 0.01);
}

// Edits continue a solve with groups: the panel dimmed and its reflectance changed, a polygon
// forced to subdivide, the light made brighter: the groups still add up to the whole.
TEST(LightGroups, EditsKeepTheGroupsAddingUpToTheWhole) {
  const Hierarchy h =
      build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box_groups.des"));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.converge = 1e-2;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  int32_t panel = -1;
  for (size_t i = 0; i < h.objects.size(); ++i)
    if (h.objects[i].group == "panel") panel = int32_t(i);
  ASSERT_GE(panel, 0);
  Material m = s.solution.materials[size_t(panel)];
  m.emission *= 0.5f;
  m.reflectance *= 0.5f;
  set_material(edit_context(s), panel, m, *vis);
  force_subdivide(edit_context(s), 0, *vis);
  set_light(s.solution, s.energy, 0, h.lights[0].colour, 2.0f * h.lights[0].intensity);
  solve(s, *vis);
  double diff = 0.0, total = 0.0;
  for (size_t p = 0; p < s.solution.vertex_states.size(); ++p) {
    for (uint32_t v = 0; v < s.solution.vertex_states[p].size(); ++v) {
      const Vec3 all = s.solution.radiosity(p, v);
      const Vec3 sum = s.solution.group_radiosity(0, p, v) + s.solution.group_radiosity(1, p, v);
      diff += mean_component(glm::abs(all - sum));
      total += mean_component(glm::abs(all));
    }
  }
  EXPECT_LT(diff / total, 1e-5);
}

TEST(LightGroups, ASceneNamingNoGroupHasNone) {
  const Hierarchy h = build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box.des"));
  EXPECT_EQ(light_group_names(h), (std::vector<std::string>{""}));
  const SolverState s = make_solver_state(h, SolverOptions{});
  EXPECT_EQ(s.solution.group_count, 0u);
  EXPECT_TRUE(s.solution.group_states.empty());
  EXPECT_TRUE(s.options.overshoot);
}

}  // namespace
}  // namespace rad
