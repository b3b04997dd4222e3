// Editing materials and lights between shots continues the same solve to the new answer.
#include "solver/edits.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <map>

#include "scene_builder.h"
#include "solver/gather.h"
#include "solver/shoot.h"
#include "solver/solver.h"

namespace rad {
namespace {

// A closed box with a ceiling lamp, a coloured wall, a black (rho = 0) wall and a blocker.
SceneDescription edit_scene(Vec3 lamp_e, Vec3 left_rho, Vec3 black_rho) {
  SceneDescription d;
  const Vec3 w(0.6f, 0.55f, 0.5f);
  const Vec3 p[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  testing::add_quad(d, "floor", p[0], p[1], p[2], p[3], w, Vec3(0), 1);
  testing::add_quad(d, "ceiling", p[4], p[7], p[6], p[5], w, Vec3(0), 1);
  testing::add_quad(d, "front", p[0], p[4], p[5], p[1], w, Vec3(0), 1);
  testing::add_quad(d, "back", p[3], p[2], p[6], p[7], black_rho, Vec3(0), 1);
  testing::add_quad(d, "left", p[0], p[3], p[7], p[4], left_rho, Vec3(0), 1);
  testing::add_quad(d, "right", p[1], p[5], p[6], p[2], w, Vec3(0), 1);
  testing::add_quad(d, "lamp", {0.4f, 0.4f, 0.99f}, {0.4f, 0.6f, 0.99f}, {0.6f, 0.6f, 0.99f},
                    {0.6f, 0.4f, 0.99f}, Vec3(0.5f), lamp_e);
  testing::add_quad(d, "blocker", {0.3f, 0.3f, 0.4f}, {0.7f, 0.3f, 0.4f}, {0.7f, 0.7f, 0.4f},
                    {0.3f, 0.7f, 0.4f}, w, Vec3(0));
  return d;
}

const Vec3 kLamp(5.0f), kLeft(0.6f, 0.3f, 0.2f), kBlack(0.0f);

SolverOptions options() {
  SolverOptions o;
  o.converge = 2e-4;
  o.subdivision_threshold = 0.1f;  // coarser than the default: this compares two solves
  return o;
}

int32_t object_named(const Hierarchy& h, const std::string& name) {
  for (size_t i = 0; i < h.objects.size(); ++i)
    if (h.objects[i].name == name) return int32_t(i);
  return -1;
}

// Worst difference at the polygons' corners (computed exactly in both solves), over the mean.
double worst_difference(const SolverState& a, const SolverState& b) {
  double mean = 0, worst = 0;
  int n = 0;
  for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < 3; ++v) mean += mean_component(b.solution.radiosity(p, v)), ++n;
  }
  mean /= n;
  for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < 3; ++v) {
      worst = std::max(
          worst,
          double(max_component(glm::abs(a.solution.radiosity(p, v) - b.solution.radiosity(p, v)))));
    }
  }
  return worst / mean;
}

// Solves the base scene, applies `edit` to its state, continues; then solves the edited scene
// from scratch; returns the worst corner difference.
double edit_then_continue(const std::string& object, const Material& m, Vec3 lamp, Vec3 left,
                          Vec3 black) {
  const Hierarchy base_h = build_hierarchy(edit_scene(kLamp, kLeft, kBlack));
  const auto base_vis = make_visibility_backend(BackendKind::Embree, base_h);
  SolverState edited = make_solver_state(base_h, options());
  solve(edited, *base_vis);
  const int64_t shots_before = edited.shots.count;
  set_material(edit_context(edited), object_named(base_h, object), m, *base_vis);
  EXPECT_GT(edited.energy.unshot_fraction(), options().converge)
      << "the edit must leave work to do";
  solve(edited, *base_vis);
  EXPECT_GT(edited.shots.count, shots_before);

  const Hierarchy fresh_h = build_hierarchy(edit_scene(lamp, left, black));
  const auto fresh_vis = make_visibility_backend(BackendKind::Embree, fresh_h);
  SolverState fresh = make_solver_state(fresh_h, options());
  solve(fresh, *fresh_vis);
  const double d = worst_difference(edited, fresh);
  std::printf("%s edit: worst corner difference %.4f%% of the mean radiosity\n", object.c_str(),
              100 * d);
  return d;
}

TEST(Edits, RaisingALightConvergesToAFreshSolve) {
  const Vec3 brighter(8.0f);
  EXPECT_LE(edit_then_continue("lamp", {Vec3(0.5f), brighter}, brighter, kLeft, kBlack), 0.005);
}

TEST(Edits, DimmingALightShootsNegativeEnergyAndConverges) {
  const Vec3 dimmer(2.0f);
  EXPECT_LE(edit_then_continue("lamp", {Vec3(0.5f), dimmer}, dimmer, kLeft, kBlack), 0.005);
}

TEST(Edits, TurningTheOnlyLightOffShootsItsLightBackOutToDarkness) {
  // Nothing emits afterwards, so the emitted energy is zero (or a rounding leftover of either
  // sign): convergence must be judged against the energy there was, or the negative energy is
  // never shot (a negative leftover reads as converged) or shot forever (a tiny positive one).
  const Hierarchy h = build_hierarchy(edit_scene(kLamp, kLeft, kBlack));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, options());
  solve(s, *vis);
  double lit = 0.0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p)
    lit += mean_component(s.solution.radiosity(p, 0));
  ASSERT_GT(lit, 0.0);
  const int64_t shots_before = s.shots.count;
  set_material(edit_context(s), object_named(h, "lamp"), {Vec3(0.5f), Vec3(0.0f)}, *vis);
  EXPECT_GT(s.energy.unshot_fraction(), options().converge) << "the edit must leave work to do";
  EXPECT_EQ(solve(s, *vis), StopReason::Converged);
  EXPECT_GT(s.shots.count, shots_before);
  EXPECT_LT(s.shots.count, shots_before + 2000) << "converges, not shooting rounding leftovers";
  double left = 0.0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p)
    left += std::abs(mean_component(s.solution.radiosity(p, 0)));
  EXPECT_LT(left, 0.01 * lit) << "the scene goes dark";
}

TEST(Edits, ChangingAColourConvergesToAFreshSolve) {
  const Vec3 green(0.2f, 0.7f, 0.3f);
  EXPECT_LE(edit_then_continue("left", {green, Vec3(0)}, kLamp, green, kBlack), 0.005);
}

TEST(Edits, AColourOfTheSameMeanReflectanceConvergesToAFreshSolve) {
  // The edit's unshot radiosity is +0.2 H in red and -0.2 H in green: its mean over the
  // channels is small, yet it must be shot.
  const Vec3 same_mean(0.4f, 0.5f, 0.2f);  // kLeft is (0.6, 0.3, 0.2)
  EXPECT_LE(edit_then_continue("left", {same_mean, Vec3(0)}, kLamp, same_mean, kBlack), 0.005);
}

TEST(Edits, AColourChangeOfZeroMeanInAGreyRoomIsShotToo) {
  // Everything grey under a white lamp, so H is grey: turning a grey wall reddish at the same
  // mean reflectance gives unshot radiosity (+x, -x, 0), whose mean over the channels is zero
  // (to rounding). Judged by that mean the edit was never shot and the solve stayed converged.
  const Vec3 grey(0.5f), reddish(0.6f, 0.4f, 0.5f);
  auto scene = [&](Vec3 left) {
    SceneDescription d = edit_scene(kLamp, left, grey);
    for (ObjectDescription& o : d.objects) {
      if (o.name != "left" && o.name != "lamp" && o.name != "back") o.material.reflectance = grey;
    }
    return d;
  };
  const Hierarchy base_h = build_hierarchy(scene(grey));
  const auto base_vis = make_visibility_backend(BackendKind::Embree, base_h);
  SolverState edited = make_solver_state(base_h, options());
  solve(edited, *base_vis);
  set_material(edit_context(edited), object_named(base_h, "left"), {reddish, Vec3(0)}, *base_vis);
  EXPECT_GT(edited.energy.unshot_fraction(), options().converge)
      << "the edit must leave work to do";
  solve(edited, *base_vis);

  const Hierarchy fresh_h = build_hierarchy(scene(reddish));
  const auto fresh_vis = make_visibility_backend(BackendKind::Embree, fresh_h);
  SolverState fresh = make_solver_state(fresh_h, options());
  solve(fresh, *fresh_vis);
  EXPECT_LE(worst_difference(edited, fresh), 0.005);
}

TEST(Edits, ReflectanceFromZeroConvergesToAFreshSolve) {
  const Vec3 grey(0.7f);
  EXPECT_LE(edit_then_continue("back", {grey, Vec3(0)}, kLamp, kLeft, grey), 0.005);
}

TEST(Edits, RejectsANonPureOrAnOutOfRangeMaterial) {
  const Hierarchy h = build_hierarchy(edit_scene(kLamp, kLeft, kBlack));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, options());
  EXPECT_THROW(set_material(edit_context(s), -1, {}, *vis), Error);
  EXPECT_THROW(set_material(edit_context(s), object_named(h, "floor"), {Vec3(1.5f), Vec3(0)}, *vis),
               Error);
  EXPECT_THROW(
      set_material(edit_context(s), object_named(h, "floor"), {Vec3(0.5f), Vec3(-1)}, *vis), Error);
}

TEST(Edits, ForcedSubdivisionGivesNewVerticesTheirExactRadiosity) {
  const Hierarchy h = build_hierarchy(edit_scene(kLamp, kLeft, kBlack));
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o = options();
  o.subdivision_threshold = 1e6f;  // no automatic subdivision: the floor stays coarse
  o.max_size = 1e6f;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  const int32_t floor_polygon = int32_t(h.objects[size_t(object_named(h, "floor"))].first_triangle);
  const size_t before = s.solution.mesh.polygons[size_t(floor_polygon)].vertex_count();
  const size_t added = force_subdivide(edit_context(s), floor_polygon, *vis);
  const PolygonMesh& m = s.solution.mesh.polygons[size_t(floor_polygon)];
  const std::vector<VertexState>& vs = s.solution.vertex_states[size_t(floor_polygon)];
  EXPECT_EQ(added, 3u);
  EXPECT_EQ(m.vertex_count(), before + 3);
  // Exact: the first new vertex holds what every logged shot gives a point there, not the
  // mean of its edge's ends.
  const Vec3 mid = m.positions[before];
  float interpolated = 0;
  for (const auto& [key, v] : m.midpoints.entries()) {
    if (v == before) {
      interpolated = 0.5f * (vs[key >> 32].irradiance.x + vs[key & 0xffffffffu].irradiance.x);
    }
  }
  GatherScratch sc;
  Vec3 expected(0.0f);
  const Vec3 centroid = (m.positions[0] + m.positions[1] + m.positions[2]) / 3.0f;
  for (const ShotSource& src : s.shots.sources) {
    if (!may_receive(*s.solution.hierarchy, s.scene.clusters, size_t(floor_polygon), src)) continue;
    expected += gather_from_source(mid, h.triangles.normal[size_t(floor_polygon)], centroid, src,
                                   *vis, gather_settings(s), sc);
  }
  EXPECT_FLOAT_EQ(vs[before].irradiance.x, expected.x);
  EXPECT_NE(vs[before].irradiance.x, interpolated) << "computed, not the mean of its ends";
}

// A room of 4 x 3 x 5 m with a table, lit by point lights (no emitting surface).
Light room_light(const std::string& name, Vec3 at, float candela, Vec3 colour = Vec3(1.0f)) {
  Light l;
  l.name = name;
  l.kind = LightKind::Point;
  l.position = at;
  l.direction = Vec3(0.0f, -1.0f, 0.0f);
  l.intensity = candela;
  l.colour = colour;
  return l;
}

Hierarchy lit_room(const std::vector<Light>& lights) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(4.0f, 3.0f, 5.0f), Vec3(0.6f, 0.55f, 0.5f),
                          Vec3(0.0f), 2);
  testing::add_quad(d, "table", Vec3(1, 1, 1), Vec3(3, 1, 1), Vec3(3, 1, 3), Vec3(1, 1, 3),
                    Vec3(0.3f, 0.5f, 0.7f), Vec3(0.0f), 2);
  Hierarchy h = build_hierarchy(d);
  h.lights = lights;
  return h;
}

const Light kLampA = room_light("a", Vec3(1.3f, 2.6f, 3.1f), 80.0f);
const Light kLampB = room_light("b", Vec3(3.0f, 2.2f, 1.5f), 50.0f, Vec3(1.0f, 0.8f, 0.6f));

// Over every vertex both solutions have (the same position in the same polygon: a fresh solve
// may subdivide elsewhere), the mean per-vertex difference over the mean radiosity.
double mean_vertex_difference(const SolverState& a, const SolverState& b, size_t* compared) {
  double diff = 0.0, sum = 0.0;
  size_t n = 0;
  for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& ma = a.solution.mesh.polygons[p];
    const PolygonMesh& mb = b.solution.mesh.polygons[p];
    std::map<std::array<float, 3>, uint32_t> at;
    for (uint32_t v = 0; v < mb.vertex_count(); ++v)
      at[{mb.positions[v].x, mb.positions[v].y, mb.positions[v].z}] = v;
    for (uint32_t v = 0; v < ma.vertex_count(); ++v) {
      const auto it = at.find({ma.positions[v].x, ma.positions[v].y, ma.positions[v].z});
      if (it == at.end()) continue;
      const Vec3 ba = a.solution.radiosity(p, v), bb = b.solution.radiosity(p, it->second);
      for (int k = 0; k < 3; ++k) diff += std::abs(double(ba[k]) - double(bb[k]));
      sum += double(bb.x) + double(bb.y) + double(bb.z);
      ++n;
    }
  }
  *compared = n;
  return sum > 0.0 ? diff / sum : 1.0;
}

// That `edited`, converged after its edits, is within 1% per vertex of a fresh solve of the room
// lit by `lights` (`what` names the case in the printed figure).
void expect_fresh_solve_of(const SolverState& edited, std::vector<Light> lights, const char* what) {
  const Hierarchy fresh_h = lit_room(std::move(lights));
  const auto fresh_vis = make_visibility_backend(BackendKind::Embree, fresh_h);
  SolverState fresh = make_solver_state(fresh_h, options());
  solve(fresh, *fresh_vis);
  size_t compared = 0;
  const double d = mean_vertex_difference(edited, fresh, &compared);
  std::printf("%s: mean vertex difference %.4f%% over %zu vertices\n", what, 100 * d, compared);
  EXPECT_GT(compared, 100u) << what;
  EXPECT_LE(d, 0.01) << what;
}

TEST(Edits, ALightsIntensityAndColourContinueToAFreshSolveOfTheEditedScene) {
  const Hierarchy h = lit_room({kLampA, kLampB});
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState edited = make_solver_state(h, options());
  EXPECT_EQ(solve(edited, *vis), StopReason::Converged);
  const int64_t shots_before = edited.shots.count;
  const Vec3 orange(1.0f, 0.5f, 0.2f);
  set_light(edited.solution, edited.energy, 0, orange, 2.0f * kLampA.intensity);
  EXPECT_GT(edited.energy.unshot_fraction(), options().converge) << "the edit leaves work";
  EXPECT_EQ(solve(edited, *vis), StopReason::Converged);
  EXPECT_GT(edited.shots.count, shots_before) << "continued, not restarted";
  EXPECT_EQ(edited.solution.lights[0].intensity, 2.0f * kLampA.intensity);

  Light a2 = kLampA;
  a2.colour = orange;
  a2.intensity = 2.0f * kLampA.intensity;
  expect_fresh_solve_of(edited, {a2, kLampB}, "light edit");
}

TEST(Edits, SwitchingALightOffLeavesOnlyTheOtherLightsLight) {
  const Hierarchy h = lit_room({kLampA, kLampB});
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState edited = make_solver_state(h, options());
  solve(edited, *vis);
  set_light(edited.solution, edited.energy, 0, kLampA.colour, 0.0f);
  EXPECT_EQ(solve(edited, *vis), StopReason::Converged);

  expect_fresh_solve_of(edited, {kLampB}, "light off");

  // And on again: back to the scene's own solution.
  set_light(edited.solution, edited.energy, 0, kLampA.colour, kLampA.intensity);
  EXPECT_EQ(solve(edited, *vis), StopReason::Converged);
  expect_fresh_solve_of(edited, {kLampA, kLampB}, "light on again");
}

TEST(Edits, ALightEditBeforeTheFirstShotIsTheEditedScenesOwnStart) {
  // Before the light has shot, the edit changes what it will shoot: no second shot of it.
  const Hierarchy h = lit_room({kLampA});
  SolverState s = make_solver_state(h, options());
  set_light(s.solution, s.energy, 0, Vec3(0.5f, 1.0f, 1.0f), 3.0f * kLampA.intensity);
  EXPECT_EQ(s.energy.light_unshot[0], Vec3(1.5f, 3.0f, 3.0f));
  EXPECT_NEAR(s.energy.emitted_energy, s.energy.light_power[0] * 2.5,
              1e-6 * s.energy.emitted_energy);
}

// A light the scene gives intensity 0 shoots in units of intensity 1 (light_unit): an edit turns
// it on, and the solve continues to the scene's with it on.
TEST(Edits, ALightTheSceneLeavesOffTurnsOnToAFreshSolveWithItOn) {
  Light off = kLampB;
  off.intensity = 0.0f;
  const Hierarchy h = lit_room({kLampA, off});
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState edited = make_solver_state(h, options());
  EXPECT_EQ(edited.energy.light_unshot[1], Vec3(0.0f));
  solve(edited, *vis);
  set_light(edited.solution, edited.energy, 1, kLampB.colour, kLampB.intensity);
  EXPECT_EQ(edited.energy.light_unshot[1], kLampB.colour * kLampB.intensity);
  EXPECT_EQ(solve(edited, *vis), StopReason::Converged);
  expect_fresh_solve_of(edited, {kLampA, kLampB}, "light left off, turned on");
}

TEST(Edits, RejectsAMissingLightOrABadValue) {
  const Hierarchy h = lit_room({kLampA, kLampB});
  SolverState s = make_solver_state(h, options());
  EXPECT_THROW(set_light(s.solution, s.energy, 2, Vec3(1.0f), 1.0f), Error);
  EXPECT_THROW(set_light(s.solution, s.energy, -1, Vec3(1.0f), 1.0f), Error);
  EXPECT_THROW(set_light(s.solution, s.energy, 0, Vec3(1.0f), -1.0f), Error);
  EXPECT_THROW(
      set_light(s.solution, s.energy, 0, Vec3(1.0f), std::numeric_limits<float>::infinity()),
      Error);
  EXPECT_THROW(set_light(s.solution, s.energy, 0, Vec3(-1.0f, 1.0f, 1.0f), 1.0f), Error);
  EXPECT_EQ(s.energy.light_unshot[0], kLampA.colour) << "a refused edit changes nothing";
}

}  // namespace
}  // namespace rad
