// Lights of the scene as shooters: exact illuminance where exact answers exist, energy, and the
// backends agreeing on lit scenes.
#include "solver/light_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "scene/ies_reader.h"
#include "scene_builder.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A 4 m x 4 m floor at y = 0 facing up, black (no interreflection), cut into 8 x 8 quads.
SceneDescription black_floor() {
  SceneDescription d;
  testing::add_quad(d, "floor", Vec3(-2, 0, 2), Vec3(2, 0, 2), Vec3(2, 0, -2), Vec3(-2, 0, -2),
                    Vec3(0.0f), Vec3(0.0f), 8);
  return d;
}

Light point_light(const Vec3& at, float candela) {
  Light l;
  l.name = "lamp";
  l.kind = LightKind::Point;
  l.position = at;
  l.direction = Vec3(0.0f, -1.0f, 0.0f);
  l.intensity = candela;
  return l;
}

SolverState solve_lit(const Hierarchy& h, BackendKind backend = BackendKind::Embree,
                      SolverOptions o = {}) {
  const auto vis = make_visibility_backend(backend, h);
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  return s;
}

// Every vertex of the floor against `expected(x)`, relative to the largest value.
template <typename F>
void expect_every_vertex(const SolverState& s, F expected, float tolerance, size_t* checked) {
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      const float want = expected(m.positions[v]);
      const float got = s.solution.vertex_states[p][v].irradiance.x;
      if (want < 0.0f) continue;  // not checked there
      ++*checked;
      ASSERT_NEAR(got, want, tolerance * std::max(want, 1e-3f))
          << "at " << m.positions[v].x << " " << m.positions[v].y << " " << m.positions[v].z;
    }
  }
}

TEST(Lights, APointLightGivesEveryVertexIhOverRCubed) {
  Hierarchy h = build_hierarchy(black_floor());
  const Vec3 at(0.3f, 2.0f, -0.7f);
  h.lights.push_back(point_light(at, 100.0f));
  const SolverState s = solve_lit(h);
  EXPECT_EQ(s.shots.count, 1);
  size_t checked = 0;
  expect_every_vertex(
      s,
      [&](const Vec3& x) {
        const float r = glm::length(at - x);
        return 100.0f * at.y / (r * r * r);
      },
      1e-3f, &checked);
  EXPECT_GT(checked, 200u);
}

// The floor and its lamp cut finer, moved, turned about a skew axis and scaled: every vertex
// still gets I h / r^3 of its own placement (h its height over the floor's plane).
struct Placement {
  const char* name;
  int cuts;
  Vec3 move;
  float degrees;
  float scale;
};

class LightPlacement : public ::testing::TestWithParam<Placement> {};

TEST_P(LightPlacement, APointLightGivesEveryVertexIhOverRCubedWhereverItStands) {
  const Placement pl = GetParam();
  const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(pl.degrees),
                                               glm::normalize(Vec3(1.0f, 2.0f, 3.0f))));
  auto place = [&](const Vec3& p) { return turn * (p * pl.scale) + pl.move; };
  SceneDescription d;
  testing::add_quad(d, "floor", place(Vec3(-2, 0, 2)), place(Vec3(2, 0, 2)), place(Vec3(2, 0, -2)),
                    place(Vec3(-2, 0, -2)), Vec3(0.0f), Vec3(0.0f), pl.cuts);
  Hierarchy h = build_hierarchy(d);
  const Vec3 at = place(Vec3(0.3f, 2.0f, -0.7f)), up = turn * Vec3(0.0f, 1.0f, 0.0f);
  h.lights.push_back(point_light(at, 100.0f));
  const SolverState s = solve_lit(h);
  size_t checked = 0;
  expect_every_vertex(
      s,
      [&](const Vec3& x) {
        const float r = glm::length(at - x), height = glm::dot(at - x, up);
        return 100.0f * height / (r * r * r);
      },
      1e-3f, &checked);
  EXPECT_GT(checked, 200u);
}

INSTANTIATE_TEST_SUITE_P(
    Placements, LightPlacement,
    ::testing::Values(Placement{"AsBuilt", 8, Vec3(0.0f), 0.0f, 1.0f},
                      Placement{"CutFiner", 32, Vec3(0.0f), 0.0f, 1.0f},
                      Placement{"Moved", 8, Vec3(12.34f, -5.6f, 7.89f), 0.0f, 1.0f},
                      Placement{"Turned", 8, Vec3(0.0f), 33.0f, 1.0f},
                      Placement{"ScaledUp", 8, Vec3(0.0f), 0.0f, 10.0f},
                      Placement{"ScaledDownTurnedMoved", 8, Vec3(-3.0f, 1.0f, 2.0f), 71.0f, 0.01f}),
    [](const auto& test) { return std::string(test.param.name); });

TEST(Lights, OneCandelaOneMetreStraightAboveGivesOneLux) {
  Hierarchy h = build_hierarchy(black_floor());
  h.lights.push_back(point_light(Vec3(0.0f, 1.0f, 0.0f), 1.0f));
  const SolverState s = solve_lit(h);
  // The floor's centre is a vertex of the 8 x 8 grid.
  bool found = false;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      if (glm::length(m.positions[v]) > 1e-6f) continue;
      found = true;
      EXPECT_NEAR(s.solution.vertex_states[p][v].irradiance.y, 1.0f, 1e-3f);
    }
  }
  EXPECT_TRUE(found);
}

TEST(Lights, AnIesLightGivesEveryVertexItsTablesCandelaInterpolated) {
  // A downlight of I(gamma) = 1000 cos(gamma) candela, tabulated every 5 degrees from the nadir
  // to 90 (rotationally symmetric), 1.2 m over the floor and turned a little: every vertex
  // in front gets I(gamma) h / r^3, the table interpolated between its angles (the
  // interpolation's error for a cosine 5 degrees apart is below 0.1%).
  std::string ies = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 19 1 1 2 0 0 0\n1 1 10\n";
  for (int k = 0; k <= 90; k += 5) ies += std::to_string(k) + " ";
  ies += "\n0\n";
  for (int k = 0; k <= 90; k += 5)
    ies += std::to_string(1000.0 * std::cos(double(k) * std::numbers::pi / 180.0)) + " ";
  ies += "\n";
  Hierarchy h = build_hierarchy(black_floor());
  Light l = point_light(Vec3(0.2f, 1.2f, 0.1f), 1.0f);
  l.photometry = std::make_shared<const Photometry>(parse_ies(ies, "cosine.ies"));
  l.direction = glm::normalize(Vec3(0.1f, -1.0f, 0.05f));
  l.photometric_up = default_photometric_up(l.direction);
  h.lights.push_back(l);
  const SolverState s = solve_lit(h);
  size_t checked = 0;
  expect_every_vertex(
      s,
      [&](const Vec3& x) {
        const Vec3 d = x - l.position;
        const float r = glm::length(d);
        const float cos_gamma = glm::dot(d / r, l.direction);
        if (cos_gamma <= 0.01f) return 0.0f;
        return 1000.0f * cos_gamma * l.position.y / (r * r * r);
      },
      5e-3f, &checked);
  EXPECT_GT(checked, 200u);
}

TEST(Lights, ASpotLightIsExactInsideItsInnerConeAndDarkOutsideItsOuter) {
  Hierarchy h = build_hierarchy(black_floor());
  const Vec3 at(0.0f, 1.5f, 0.0f);
  Light l = point_light(at, 250.0f);
  l.kind = LightKind::Spot;
  l.inner_cone = 20.0f * kPi / 180.0f;
  l.outer_cone = 30.0f * kPi / 180.0f;
  h.lights.push_back(l);
  const SolverState s = solve_lit(h);
  size_t inside = 0, outside = 0;
  expect_every_vertex(
      s,
      [&](const Vec3& x) {
        const float angle = std::acos(glm::dot(glm::normalize(x - at), Vec3(0, -1, 0)));
        if (angle > l.outer_cone + 1e-3f) return 0.0f;
        if (angle >= l.inner_cone - 1e-3f) return -1.0f;
        const float r = glm::length(at - x);
        return 250.0f * at.y / (r * r * r);
      },
      1e-3f, &inside);
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      const float angle = std::acos(glm::dot(glm::normalize(m.positions[v] - at), Vec3(0, -1, 0)));
      if (angle <= l.outer_cone + 1e-3f) continue;
      ++outside;
      EXPECT_EQ(s.solution.vertex_states[p][v].irradiance, Vec3(0.0f));
    }
  }
  EXPECT_GT(inside, 50u);
  EXPECT_GT(outside, 50u);
}

TEST(Lights, TheSunGivesECosThetaAndNothingInTheUmbraOfABlackBlock) {
  SceneDescription d = black_floor();
  // A black box 1 m on a side, 0.5 m above the floor's centre.
  testing::add_closed_box(d, Vec3(-0.5f, 0.5f, -0.5f), Vec3(0.5f, 1.5f, 0.5f), Vec3(0.0f),
                          Vec3(0.0f));
  // Its faces face inwards: turn each triangle so they face out and cast shadows either way.
  for (ObjectDescription& o : d.objects) {
    if (o.name == "floor") continue;
    for (auto& t : o.triangles) std::swap(t[1], t[2]);
  }
  Hierarchy h = build_hierarchy(d);
  Light sun;
  sun.name = "sun";
  sun.kind = LightKind::Directional;
  const float theta = 30.0f * kPi / 180.0f;
  sun.direction = Vec3(std::sin(theta), -std::cos(theta), 0.0f);
  sun.intensity = 1000.0f;
  h.lights.push_back(sun);
  const SolverState s = solve_lit(h);
  // The umbra on the floor: the block's shadow less the penumbra's width (the sun's half
  // angle over the 1.5 m the block's top stands up, with room).
  const float lean = std::tan(theta), blur = 1.5f * std::tan(0.6f * kPi / 180.0f) + 0.1f;
  size_t lit = 0, dark = 0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    if (h.objects[size_t(h.triangles.object[p])].name != "floor") continue;
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      const Vec3 x = m.positions[v];
      const float got = s.solution.vertex_states[p][v].irradiance.x;
      // Shadow of the block: x - lean * y over [0.5, 1.5] of height, |z| < 0.5.
      const bool in_z = std::abs(x.z)<0.5f - blur, out_z = std::abs(x.z)> 0.5f + blur;
      const float lo = -0.5f + 0.5f * lean, hi = 0.5f + 1.5f * lean;
      if (in_z && x.x > lo + blur && x.x < hi - blur) {
        ++dark;
        EXPECT_EQ(got, 0.0f) << x.x << " " << x.z;
      } else if (out_z || x.x < lo - blur || x.x > hi + blur) {
        ++lit;
        EXPECT_NEAR(got, 1000.0f * std::cos(theta), 1e-3f * 1000.0f) << x.x << " " << x.z;
      }
    }
  }
  EXPECT_GT(dark, 10u);
  EXPECT_GT(lit, 100u);
}

TEST(Lights, AFirstShotInAClosedRoomDepositsThePowerTheLightEmits) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(4.0f, 3.0f, 5.0f), Vec3(0.5f), Vec3(0.0f), 4);
  Hierarchy h = build_hierarchy(d);
  h.lights.push_back(point_light(Vec3(1.3f, 2.2f, 3.1f), 80.0f));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.max_shots = 1;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  ASSERT_EQ(s.shots.count, 1);
  // H integrated over every leaf element (linear over each), against 4 pi I.
  double deposited = 0.0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const std::vector<VertexState>& vs = s.solution.vertex_states[p];
    for_each_leaf_vertex_sum(
        s.solution.mesh.polygons[p], [&](uint32_t v) { return vs[v].irradiance; },
        [&](float area, Vec3 sum) { deposited += double(area) * double(sum.x) / 3.0; });
  }
  const double power = 4.0 * std::numbers::pi * 80.0;
  EXPECT_NEAR(deposited, power, 5e-3 * power);
  EXPECT_NEAR(s.energy.light_power[0], 4.0 * std::numbers::pi * 80.0, 1e-3 * power);
}

// rad-gen building --downlights: each room's light is its ceiling panel's far field, as bright
// on its axis and of the same power (tools/bench_lights compares their solves).
TEST(Lights, TheBuildingsDownlightIsItsPanelsFarFieldAndPower) {
  RoomLighting downlights{RoomLighting::Kind::Downlight, nullptr};
  downlights.downlight =
      std::make_shared<const Photometry>(parse_ies(downlight_ies(), "downlight.ies"));
  const Photometry& table = *downlights.downlight;
  EXPECT_NEAR(table.candela_at(0.0f, 0.0f), 8.0 / std::numbers::pi, 1e-5);
  EXPECT_NEAR(table.candela_at(60.0f, 123.0f), 4.0 / std::numbers::pi, 1e-5);
  EXPECT_EQ(table.candela_at(120.0f, 0.0f), 0.0f);
  const Hierarchy lit =
      build_hierarchy(generate_scene(SceneKind::Building, 3200, 1, -1, downlights));
  const Hierarchy panels = build_hierarchy(generate_scene(SceneKind::Building, 3200, 1));
  ASSERT_EQ(lit.lights.size(), 2u);
  EXPECT_TRUE(panels.lights.empty());
  const SolverState a = make_solver_state(lit, SolverOptions{});
  const SolverState b = make_solver_state(panels, SolverOptions{});
  EXPECT_NEAR(a.energy.emitted_energy, b.energy.emitted_energy, 1e-3 * b.energy.emitted_energy);
}

TEST(Lights, EveryBackendGivesTheSameBitsOnALitScene) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(4.0f, 3.0f, 5.0f), Vec3(0.6f), Vec3(0.0f), 2);
  testing::add_quad(d, "table", Vec3(1, 1, 1), Vec3(3, 1, 1), Vec3(3, 1, 3), Vec3(1, 1, 3),
                    Vec3(0.7f), Vec3(0.0f), 2);
  Hierarchy h = build_hierarchy(d);
  h.lights.push_back(point_light(Vec3(2.2f, 2.5f, 2.1f), 60.0f));
  Light spot = point_light(Vec3(3.5f, 2.8f, 4.5f), 300.0f);
  spot.kind = LightKind::Spot;
  spot.direction = glm::normalize(Vec3(-1.0f, -1.0f, -1.0f));
  spot.inner_cone = 0.3f, spot.outer_cone = 0.5f;
  h.lights.push_back(spot);
  SolverOptions o;
  o.max_shots = 12;
  const SolverState a = solve_lit(h, BackendKind::Embree, o);
  for (BackendKind other : {BackendKind::Grid, BackendKind::Brute}) {
    const SolverState b = solve_lit(h, other, o);
    ASSERT_EQ(a.solution.mesh.polygons.size(), b.solution.mesh.polygons.size());
    for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
      ASSERT_EQ(a.solution.vertex_states[p].size(), b.solution.vertex_states[p].size()) << p;
      for (size_t v = 0; v < a.solution.vertex_states[p].size(); ++v)
        ASSERT_EQ(a.solution.vertex_states[p][v].irradiance,
                  b.solution.vertex_states[p][v].irradiance);
    }
  }
}

}  // namespace
}  // namespace rad
