// The original's per-object flags (design §8) in the solver, on every backend: an object that
// casts no shadows is invisible to shadow rays, one that receives none takes every visibility
// term as 1, and an object with a Lights list lights only itself and what it lists.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "scene/parser.h"
#include "scene_builder.h"
#include "solver/solver.h"

namespace rad {
namespace {

using testing::Solved;

// A 4 x 4 floor (y = 0, facing up) under a 2 x 2 light (y = 2, facing down), and a black 1 x 1
// card: at y = 1 over the middle of the floor (`card_flags` on it), or, with `card_away`, in the
// plane x = 0 where no segment between the light and the floor meets it. The card is black, so
// it changes the floor only through shadows, and both places keep the scene's box and area.
std::string scene(const std::string& floor_flags, const std::string& light_flags,
                  const std::string& card_flags, bool card_away) {
  const std::string card =
      card_away ? "<0 0.5 1.5> <0 0.5 2.5> <0 1.5 2.5>  <0 0.5 1.5> <0 1.5 2.5> <0 1.5 1.5>"
                : "<1.5 1 1.5> <1.5 1 2.5> <2.5 1 2.5>  <1.5 1 1.5> <2.5 1 2.5> <2.5 1 1.5>";
  return "\"flags\"\n"
         "Object \"floor\" Pure " +
         floor_flags +
         " { Reflectivity 0.5 Color <1 1 1> Emission 0\n"
         "  Data { <0 0 0> <0 0 4> <4 0 4>  <0 0 0> <4 0 4> <4 0 0> } }\n"
         "Object \"other floor\" Pure { Reflectivity 0.5 Color <1 1 1> Emission 0\n"
         "  Data { <4 0 0> <4 0 4> <8 0 4>  <4 0 0> <8 0 4> <8 0 0> } }\n"
         "Object \"light\" Pure " +
         light_flags +
         " { Reflectivity 0 Color <1 1 1> Emission 10\n"
         "  Data { <1 2 1> <3 2 1> <3 2 3>  <1 2 1> <3 2 3> <1 2 3> } }\n"
         "Object \"card\" Pure " +
         card_flags +
         " { Reflectivity 0 Color <1 1 1> Emission 0\n"
         "  Data { " +
         card + " } }\n";
}

class FlaggedScene : public ::testing::TestWithParam<BackendKind> {
 protected:
  std::unique_ptr<Solved> solve_text(const std::string& text) {
    auto r = std::make_unique<Solved>();
    r->h = build_hierarchy(parse_scene_text(text, "flags.des"));
    r->vis = make_visibility_backend(GetParam(), r->h);
    SolverOptions o;
    o.sample_grid = o.max_sample_grid = 4;
    o.converge = 1e-4;
    r->s = make_solver_state(r->h, o);
    solve(r->s, *r->vis);
    return r;
  }
};

// Every vertex of the named object's polygons, in order: (position, irradiance).
std::vector<std::pair<Vec3, Vec3>> vertices_of(const Solved& r, const std::string& name) {
  std::vector<std::pair<Vec3, Vec3>> out;
  for (size_t p = 0; p < r.h.triangles.size(); ++p) {
    if (r.h.objects[size_t(r.h.triangles.object[p])].name != name) continue;
    for (uint32_t v = 0; v < r.s.solution.mesh.polygons[p].vertex_count(); ++v)
      out.push_back({r.s.solution.mesh.polygons[p].positions[v],
                     r.s.solution.vertex_states[p][v].irradiance});
  }
  return out;
}

void expect_same_floor(const Solved& a, const Solved& b) {
  const auto va = vertices_of(a, "floor"), vb = vertices_of(b, "floor");
  ASSERT_EQ(va.size(), vb.size());
  float largest = 0.0f;
  for (const auto& v : vb) largest = std::max(largest, max_component(v.second));
  ASSERT_GT(largest, 0.0f);
  for (size_t i = 0; i < va.size(); ++i) {
    ASSERT_EQ(va[i].first, vb[i].first) << i;
    EXPECT_LE(max_component(glm::abs(va[i].second - vb[i].second)), 1e-5f * largest)
        << "vertex " << i << " at " << va[i].first.x << " " << va[i].first.z;
  }
}

// The floor's least irradiance under the card's shadow (the vertices within 0.3 of its centre).
float shadowed_minimum(const Solved& r) {
  float least = 1e30f;
  for (const auto& [x, h] : vertices_of(r, "floor")) {
    if (std::abs(x.x - 2.0f) < 0.3f && std::abs(x.z - 2.0f) < 0.3f) least = std::min(least, h.x);
  }
  return least;
}

TEST_P(FlaggedScene, TheCardCastsAShadowByDefault) {
  const auto shadowed = solve_text(scene("", "", "", false));
  const auto open = solve_text(scene("", "", "", true));
  EXPECT_LT(shadowed_minimum(*shadowed), 0.5f * shadowed_minimum(*open));
}

TEST_P(FlaggedScene, AnObjectThatCastsNoShadowsIsInvisibleToShadowRays) {
  expect_same_floor(*solve_text(scene("", "", "CastsShadows No", false)),
                    *solve_text(scene("", "", "", true)));
}

TEST_P(FlaggedScene, AnObjectThatReceivesNoShadowsTakesEveryVisibilityTermAsOne) {
  expect_same_floor(*solve_text(scene("ReceivesShadows No", "", "", false)),
                    *solve_text(scene("", "", "", true)));
}

TEST_P(FlaggedScene, AnObjectWithALightsListLightsOnlyItselfAndWhatItLists) {
  const auto listed = solve_text(scene("", "Lights { \"floor\" }", "", true));
  const auto all = solve_text(scene("", "", "", true));
  for (const auto& [x, h] : vertices_of(*listed, "other floor")) {
    EXPECT_EQ(h, Vec3(0.0f)) << x.x << " " << x.z;
  }
  float lit = 0.0f;
  for (const auto& [x, h] : vertices_of(*all, "other floor")) lit = std::max(lit, h.x);
  EXPECT_GT(lit, 0.0f);  // without the list the other floor gets light
  expect_same_floor(*listed, *all);
}

TEST_P(FlaggedScene, AGroupsFlagsHoldForEverythingInside) {
  const std::string text = "\"nested\"\nObject \"room\" Assembly CastsShadows No {\n" +
                           scene("", "", "", false).substr(std::string("\"flags\"\n").size()) +
                           "}\n";
  expect_same_floor(*solve_text(text), *solve_text(scene("", "", "", true)));
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, FlaggedScene,
                         ::testing::Values(BackendKind::Embree, BackendKind::Grid,
                                           BackendKind::Brute),
                         [](const auto& test) { return std::string(to_string(test.param)); });

}  // namespace
}  // namespace rad
