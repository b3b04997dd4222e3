// The session: edits queued from other threads are applied between shots and continue the same
// solve (Chen 1990); snapshots are consistent; pause, resume and restart do what they say.
#include "serve/session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "core/error.h"
#include "serve_scene.h"
#include "solver/solver.h"

namespace rad {
namespace {

using namespace std::chrono_literals;

// Waits (up to `timeout`) for a snapshot that satisfies `ok`; returns it, or null.
std::shared_ptr<const Snapshot> wait_for(const Session& s,
                                         const std::function<bool(const Snapshot&)>& ok,
                                         std::chrono::seconds timeout = 300s) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  auto snap = s.snapshot();
  while (!ok(*snap)) {
    if (std::chrono::steady_clock::now() > end) return nullptr;
    snap = s.wait_for_snapshot(snap->version, 100ms);
  }
  return snap;
}

bool converged(const Snapshot& s) { return s.status == SessionStatus::Converged; }

// Every array of a snapshot agrees with the others.
void expect_consistent(const Snapshot& s) {
  ASSERT_TRUE(s.mesh.geometry);
  const MeshGeometry& g = *s.mesh.geometry;
  ASSERT_EQ(g.indices.size() % 3, 0u);
  EXPECT_EQ(g.face_polygon.size(), g.indices.size() / 3);
  EXPECT_EQ(s.colour.size(), g.position.size());
  EXPECT_EQ(s.mesh.display.size(), g.position.size());
  EXPECT_EQ(s.mesh.radiosity.size(), g.position.size());
  for (uint32_t i : g.indices) ASSERT_LT(i, g.position.size());
  for (const Vec3& c : s.colour) {
    ASSERT_GE(c.x, 0.0f);
    ASSERT_LE(max_component(c), 1.0f);
  }
}

// Worst difference of two states' radiosity at the polygons' corners, over the mean.
double worst_corner_difference(const SolverState& a, const SolverState& b) {
  double mean = 0.0, worst = 0.0;
  int n = 0;
  for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
    for (uint32_t v = 0; v < 3; ++v) {
      mean += mean_component(b.solution.radiosity(p, v));
      ++n;
      worst = std::max(
          worst,
          double(max_component(glm::abs(a.solution.radiosity(p, v) - b.solution.radiosity(p, v)))));
    }
  }
  return worst / (mean / n);
}

class SessionTest : public ::testing::Test {
 protected:
  SessionTest()
      : h(build_hierarchy(testing::serve_scene())),
        vis(make_visibility_backend(BackendKind::Embree, h)) {
    options.solver = testing::serve_options();
    options.solver.converge = 1e-2;  // quick; the equivalence test asks for more
    options.publish_interval = 0.0;  // a snapshot per shot
  }
  // Leaf elements below `object` before any shot.
  int64_t initial_elements(const std::string& object) const {
    return elements_per_object(make_solver_state(h, options.solver))[size_t(id(object))];
  }
  int32_t id(const std::string& name) const { return testing::object_named(h, name); }

  const Hierarchy h;
  const std::unique_ptr<VisibilityBackend> vis;
  SessionOptions options;
};

TEST_F(SessionTest, PublishesTheUnlitSceneBeforeItStarts) {
  Session s(h, *vis, options);
  const auto snap = s.snapshot();
  EXPECT_EQ(snap->version, 1u);
  EXPECT_EQ(snap->mesh_version, 1u);
  EXPECT_EQ(snap->shots, 0);
  EXPECT_EQ(snap->status, SessionStatus::Running);
  EXPECT_NEAR(snap->unshot_fraction, 1.0, 1e-9);
  EXPECT_EQ(snap->objects.size(), h.objects.size());
  EXPECT_EQ(snap->objects[size_t(id("room"))].elements, initial_elements("room"));
  EXPECT_GE(snap->objects[size_t(id("room"))].elements, int64_t(h.triangles.size()));
  EXPECT_EQ(snap->elements, initial_elements("room"));
  EXPECT_NEAR(snap->objects[size_t(id("lamp"))].controls.emission, 5.0f, 1e-6f);
  expect_consistent(*snap);
}

// With light groups, dimmers mix the groups' solutions into the colours shown: no shot more,
// and all at 1 shows the whole solve again.
TEST_F(SessionTest, DimmersMixTheLightGroupsWithoutANewSolve) {
  Hierarchy grouped = build_hierarchy(testing::serve_scene());
  grouped.objects[size_t(id("lamp"))].group = "lamp";
  Light bulb;
  bulb.name = "bulb", bulb.position = Vec3(0.3f, 0.5f, 0.5f), bulb.intensity = 0.2f;
  bulb.group = "bulb";
  grouped.lights = {bulb};
  const auto grouped_vis = make_visibility_backend(BackendKind::Embree, grouped);
  Session s(grouped, *grouped_vis, options);
  s.start();
  const auto done = wait_for(s, converged);
  ASSERT_TRUE(done);
  EXPECT_EQ(done->dimmers, (std::vector<float>{1.0f, 1.0f}));
  // The snapshot's mesh holds the groups, for the exports.
  EXPECT_EQ(done->mesh.group_names, (std::vector<std::string>{"lamp", "bulb"}));
  ASSERT_EQ(done->mesh.group_radiosity.size(), 2u);
  EXPECT_EQ(done->mesh.group_radiosity[1].size(), done->mesh.radiosity.size());
  EXPECT_THROW(s.set_dimmers({1.0f}), Error);
  s.set_dimmers({0.0f, 1.0f});
  const auto dark =
      wait_for(s, [](const Snapshot& x) { return !x.dimmers.empty() && x.dimmers[0] == 0.0f; });
  ASSERT_TRUE(dark);
  EXPECT_EQ(dark->shots, done->shots);
  EXPECT_EQ(dark->status, SessionStatus::Converged);
  auto brightness = [](const Snapshot& x) {
    double sum = 0.0;
    for (const Vec3& c : x.colour) sum += mean_component(c);
    return sum;
  };
  EXPECT_LT(brightness(*dark), brightness(*done)) << "the lamp's light is gone";
  EXPECT_GT(brightness(*dark), 0.0) << "the bulb's stays";
  // Both off: nothing but the display's ambient term (next to none once converged).
  s.set_dimmers({0.0f, 0.0f});
  const auto off =
      wait_for(s, [](const Snapshot& x) { return !x.dimmers.empty() && x.dimmers[1] == 0.0f; });
  ASSERT_TRUE(off);
  EXPECT_LT(brightness(*off), 0.05 * brightness(*done));
  s.set_dimmers({1.0f, 1.0f});
  const auto back = wait_for(
      s,
      [](const Snapshot& x) { return !x.dimmers.empty() && x.dimmers[0] == 1.0f && x.version > 0; },
      10s);
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->colour == done->colour);
}

TEST_F(SessionTest, SolvesToConvergenceThenSleeps) {
  Session s(h, *vis, options);
  s.start();
  const auto done = wait_for(s, converged);
  ASSERT_TRUE(done) << "no convergence within the time limit";
  EXPECT_LE(done->unshot_fraction, options.solver.converge);
  EXPECT_TRUE(done->exposure_locked) << "the exposure is fixed once converged";
  expect_consistent(*done);
  // Asleep: no new snapshot without an edit.
  const auto later = s.wait_for_snapshot(done->version, 300ms);
  EXPECT_EQ(later->version, done->version);
}

TEST_F(SessionTest, SnapshotsStayConsistentWhileTheSolveRuns) {
  Session s(h, *vis, options);
  s.start();
  auto prev = s.snapshot();
  int seen = 0;
  while (prev->status == SessionStatus::Running && seen < 400) {
    const auto snap = s.wait_for_snapshot(prev->version, 1s);
    expect_consistent(*snap);
    EXPECT_GE(snap->version, prev->version);
    EXPECT_GE(snap->mesh_version, prev->mesh_version);
    EXPECT_GE(snap->shots, prev->shots);
    if (snap->mesh_version == prev->mesh_version) {
      EXPECT_EQ(snap->mesh.geometry, prev->mesh.geometry)
          << "unchanged geometry is shared, not copied";
    }
    prev = snap;
    ++seen;
  }
  EXPECT_GT(prev->mesh_version, 1u) << "refinement adds elements as the solve runs";
}

// The interactive edit must land where a fresh solve with the new light lands (Chen 1990).
TEST_F(SessionTest, RaisingALightContinuesToTheFreshSolve) {
  options.solver.converge = 2e-4;
  Session s(h, *vis, options);
  s.start();
  ASSERT_TRUE(wait_for(s, converged));
  const int64_t shots_before = s.snapshot()->shots;
  ASSERT_TRUE(s.edit_material(id("lamp"), MaterialPatch{{}, {}, 8.0f}));
  const auto after =
      wait_for(s, [&](const Snapshot& x) { return converged(x) && x.shots > shots_before; });
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->objects[size_t(id("lamp"))].controls.emission, 8.0f, 1e-6f);
  s.stop();

  const Hierarchy fresh_h = build_hierarchy(testing::serve_scene(Vec3(8.0f)));
  SolverState fresh = make_solver_state(fresh_h, options.solver);
  solve(fresh, *make_visibility_backend(BackendKind::Embree, fresh_h));
  EXPECT_LE(worst_corner_difference(s.state(), fresh), 0.005);
}

TEST_F(SessionTest, PartialEditsCombineAndShowInTheNextSnapshot) {
  Session s(h, *vis, options);
  s.start();
  const int32_t left = id("left");
  ASSERT_TRUE(s.edit_material(left, MaterialPatch{Vec3(0.0f, 1.0f, 0.0f), {}, {}}));
  ASSERT_TRUE(s.edit_material(left, MaterialPatch{{}, 0.4f, {}}));
  const MaterialControls want{Vec3(0.0f, 1.0f, 0.0f), 0.4f, 0.0f};
  const auto snap =
      wait_for(s, [&](const Snapshot& x) { return x.objects[size_t(left)].controls == want; });
  ASSERT_TRUE(snap);
  EXPECT_NE(snap->notice.find("'left'"), std::string::npos) << snap->notice;
  s.stop();
  EXPECT_EQ(s.state().solution.materials[size_t(left)].reflectance, Vec3(0.0f, 0.4f, 0.0f));
}

TEST_F(SessionTest, PauseStopsShootingAndResumeContinues) {
  Session s(h, *vis, options);
  s.start();
  ASSERT_TRUE(s.pause());
  const auto paused =
      wait_for(s, [](const Snapshot& x) { return x.status == SessionStatus::Paused; });
  ASSERT_TRUE(paused);
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(s.snapshot()->shots, paused->shots);
  ASSERT_TRUE(s.resume());
  EXPECT_TRUE(wait_for(s, converged));
}

TEST_F(SessionTest, RestartSolvesAgainWithTheCurrentOrTheOriginalMaterials) {
  Session s(h, *vis, options);
  s.start();
  const auto first = wait_for(s, converged);
  ASSERT_TRUE(first);
  const int32_t lamp = id("lamp");
  ASSERT_TRUE(s.edit_material(lamp, MaterialPatch{{}, {}, 2.0f}));
  ASSERT_TRUE(wait_for(s, [&](const Snapshot& x) {
    return converged(x) && x.objects[size_t(lamp)].controls.emission == 2.0f;
  }));
  // Paused, so the restarted state stays still long enough to be looked at.
  ASSERT_TRUE(s.pause());
  ASSERT_TRUE(s.restart(false));
  const auto restarted = wait_for(
      s, [](const Snapshot& x) { return x.status == SessionStatus::Paused && x.shots == 0; });
  ASSERT_TRUE(restarted);
  EXPECT_FALSE(restarted->exposure_locked);
  EXPECT_EQ(restarted->objects[size_t(lamp)].controls.emission, 2.0f);
  EXPECT_EQ(restarted->objects[size_t(id("room"))].elements, initial_elements("room"));
  EXPECT_TRUE(restarted->history.empty());
  ASSERT_TRUE(s.resume());
  ASSERT_TRUE(wait_for(s, converged));

  ASSERT_TRUE(s.pause());
  ASSERT_TRUE(s.restart(true));
  const auto original = wait_for(s, [&](const Snapshot& x) {
    return x.status == SessionStatus::Paused && x.shots == 0 &&
           x.objects[size_t(lamp)].controls.emission == 5.0f;
  });
  ASSERT_TRUE(original);
  ASSERT_TRUE(s.resume());
  const auto again = wait_for(s, converged);
  ASSERT_TRUE(again);
  // The solver is deterministic: the same scene solved again from scratch gives the same answer.
  EXPECT_EQ(again->shots, first->shots);
  ASSERT_EQ(again->mesh.radiosity.size(), first->mesh.radiosity.size());
  for (size_t i = 0; i < first->mesh.radiosity.size(); ++i) {
    ASSERT_EQ(again->mesh.radiosity[i], first->mesh.radiosity[i]) << "vertex " << i;
  }
}

TEST_F(SessionTest, RestartKeepsTheEditedLightsOrGoesBackToTheScenes) {
  Hierarchy lit = build_hierarchy(testing::serve_scene());
  Light bulb;
  bulb.name = "bulb";
  bulb.position = Vec3(0.5f, 0.5f, 0.7f);
  bulb.intensity = 2.0f;
  lit.lights = {bulb};
  const auto lit_vis = make_visibility_backend(BackendKind::Embree, lit);
  Session s(lit, *lit_vis, options);
  ASSERT_TRUE(s.edit_light(0, LightPatch{Vec3(1.0f, 0.5f, 0.5f), 6.0f}));
  EXPECT_THROW(s.edit_light(1, LightPatch{{}, 1.0f}), Error);
  EXPECT_THROW(s.edit_light(0, LightPatch{{}, -1.0f}), Error);
  s.start();
  auto lights_are = [](float intensity) {
    return [intensity](const Snapshot& x) {
      return converged(x) && x.lights.size() == 1 && x.lights[0].intensity == intensity;
    };
  };
  ASSERT_TRUE(wait_for(s, lights_are(6.0f)));
  ASSERT_TRUE(s.restart(false));
  const auto kept = wait_for(s, [&](const Snapshot& x) {
    return lights_are(6.0f)(x) && x.notice.find("current") != std::string::npos;
  });
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->lights[0].colour, Vec3(1.0f, 0.5f, 0.5f));
  ASSERT_TRUE(s.restart(true));
  const auto reset = wait_for(s, [&](const Snapshot& x) {
    return lights_are(2.0f)(x) && x.notice.find("scene's") != std::string::npos;
  });
  ASSERT_TRUE(reset);
  EXPECT_EQ(reset->lights[0].colour, Vec3(1.0f));
  s.stop();
  EXPECT_EQ(s.state().solution.lights[0].intensity, 2.0f);
  EXPECT_EQ(s.state().energy.light_unshot[0], Vec3(0.0f)) << "shot, nothing pending";
}

TEST_F(SessionTest, ForcedSubdivisionAddsElementsUntilTheMinimumSize) {
  options.solver.min_size = 0.02f;  // a few levels above the smallest elements
  Session s(h, *vis, options);
  s.start();
  ASSERT_TRUE(wait_for(s, converged));
  const int32_t floor = id("bottom");
  const int64_t before = s.snapshot()->objects[size_t(floor)].elements;
  const int32_t polygon = int32_t(h.objects[size_t(floor)].first_triangle);
  ASSERT_TRUE(s.subdivide(polygon));
  const auto finer =
      wait_for(s, [&](const Snapshot& x) { return x.objects[size_t(floor)].elements > before; });
  ASSERT_TRUE(finer);
  EXPECT_NE(finer->notice.find("new exact vertices"), std::string::npos) << finer->notice;
  for (int i = 0; i < 6; ++i) ASSERT_TRUE(s.subdivide(polygon));
  const auto smallest = wait_for(s, [&](const Snapshot& x) {
    return x.notice.find("already at the minimum size") != std::string::npos;
  });
  EXPECT_TRUE(smallest);
}

TEST_F(SessionTest, RejectsBadEditsAndAFullQueue) {
  options.max_pending_edits = 2;
  Session s(h, *vis, options);  // not started: nothing drains the queue
  EXPECT_THROW(s.edit_material(id("room"), MaterialPatch{{}, {}, 1.0f}), Error);
  EXPECT_THROW(s.edit_material(-1, MaterialPatch{{}, {}, 1.0f}), Error);
  EXPECT_THROW(s.edit_material(id("lamp"), MaterialPatch{{}, 2.0f, {}}), Error);
  EXPECT_THROW(s.subdivide(int32_t(h.triangles.size())), Error);
  EXPECT_THROW(s.set_exposure(30.0f, false), Error);
  EXPECT_TRUE(s.subdivide(0));
  EXPECT_TRUE(s.edit_material(id("lamp"), MaterialPatch{{}, {}, 1.0f}));
  EXPECT_TRUE(s.edit_material(id("lamp"), MaterialPatch{{}, {}, 2.0f})) << "merged, not queued";
  EXPECT_FALSE(s.subdivide(1)) << "the queue is full";
}

TEST_F(SessionTest, StopsPromptlyWhileShooting) {
  Session s(h, *vis, options);
  s.start();
  std::this_thread::sleep_for(50ms);
  const auto t = std::chrono::steady_clock::now();
  s.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - t, 2s);
  EXPECT_TRUE(s.stopped());
  EXPECT_EQ(s.snapshot()->status, SessionStatus::Stopped);
}

}  // namespace
}  // namespace rad
