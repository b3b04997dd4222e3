// Shadow-ray answers kept between shots of a cluster: the same radiosity as tracing every ray.
#include "solver/kept_rays.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "scene/parser.h"
#include "scene_builder.h"
#include "scenegen/scenegen.h"
#include "solver/edits.h"
#include "solver/solver.h"

namespace rad {
namespace {

struct Solved {
  std::vector<Vec3> irradiance;
  uint64_t rays = 0, kept = 0;
  size_t kept_bytes = 0;
  bool an_end_moved = false;  // some sample's ray end moved between shots of its cluster
};

// `shots` shots, then (edit) the first emitter's emission halved and as many more: an edit
// continues the same solve (edits.h), and its negative unshot radiosity is shot again.
Solved solve_with(const Hierarchy& h, BackendKind backend, size_t kept_bytes, int shots, bool edit,
                  SolverOptions o = {}) {
  const auto vis = make_visibility_backend(backend, h);
  o.kept_rays_bytes = kept_bytes;
  SolverState s = testing::solve_shots(h, *vis, o, shots);
  if (edit) {
    for (size_t i = 0; i < h.objects.size(); ++i) {
      if (h.objects[i].kind == ObjectKind::Pure &&
          max_component(h.objects[i].material.emission) > 0) {
        set_material(edit_context(s), int32_t(i),
                     {h.objects[i].material.reflectance, 0.5f * h.objects[i].material.emission},
                     *vis);
        break;
      }
    }
    s.options.max_shots = 2 * shots;
    solve(s, *vis);
  }
  Solved out;
  for (const std::vector<VertexState>& vs : s.solution.vertex_states) {
    for (const VertexState& v : vs) out.irradiance.push_back(v.irradiance);
  }
  out.rays = s.stats.rays.rays;
  out.kept = s.stats.kept_answers;
  out.kept_bytes = s.kept.bytes;
  for (const auto& [cluster, k] : s.kept.clusters) {
    out.an_end_moved |=
        std::any_of(k.moved.begin(), k.moved.end(), [](uint32_t e) { return e > 1; });
  }
  return out;
}

void expect_identical(const Solved& a, const Solved& b) {
  ASSERT_EQ(a.irradiance.size(), b.irradiance.size()) << "different subdivision";
  EXPECT_EQ(
      0, std::memcmp(a.irradiance.data(), b.irradiance.data(), a.irradiance.size() * sizeof(Vec3)));
}

// Solves with no answers kept and with the default budget; expects the same radiosity, some
// answers kept, and every ray either traced or kept. Returns the solve with kept answers.
Solved expect_same_as_tracing_every_ray(const Hierarchy& h, BackendKind backend, int shots,
                                        bool edit, const SolverOptions& o = {}) {
  const Solved traced = solve_with(h, backend, 0, shots, edit, o);
  const Solved kept = solve_with(h, backend, SolverOptions{}.kept_rays_bytes, shots, edit, o);
  expect_identical(traced, kept);
  EXPECT_EQ(traced.kept, 0u);
  EXPECT_GT(kept.kept, 0u);
  EXPECT_EQ(kept.rays + kept.kept, traced.rays);
  return kept;
}

TEST(KeptRays, CornellBoxGetsTheRadiosityOfTracingEveryRay) {
  const Hierarchy h = build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box.des"));
  const Solved kept = expect_same_as_tracing_every_ray(h, BackendKind::Embree, 30, true);
  EXPECT_GT(kept.kept, kept.rays / 4) << "the walls shoot again and again";
}

// The grid's answers too (its walk and its shadow cache, which tries the last blocker of the
// fan first, see the same segments whether or not some of the fan's rays are kept).
TEST(KeptRays, GridGetsTheRadiosityOfTracingEveryRay) {
  const Hierarchy h = build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box.des"));
  expect_same_as_tracing_every_ray(h, BackendKind::Grid, 40, false);
}

// Curved furniture, whose strata's ray ends move from shot to shot. Its elements no smaller
// than 10 cm: what is kept does not depend on how fine the mesh is, and a coarser one runs the
// four solves in a fraction of the time.
TEST(KeptRays, FurnishedRoomGetsTheRadiosityOfTracingEveryRay) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 3000, 1));
  SolverOptions o;
  o.min_size = 0.1f;
  const Solved kept = expect_same_as_tracing_every_ray(h, BackendKind::Embree, 40, false, o);
  EXPECT_TRUE(kept.an_end_moved);
}

TEST(KeptRays, NoMoreThanTheBudget) {
  const Hierarchy h = build_hierarchy(parse_scene_file(RAD_SOURCE_DIR "/scenes/cornell_box.des"));
  const Solved all = solve_with(h, BackendKind::Embree, SolverOptions{}.kept_rays_bytes, 30, false);
  const size_t budget = all.kept_bytes / 3;
  const Solved some = solve_with(h, BackendKind::Embree, budget, 30, false);
  EXPECT_LE(some.kept_bytes, budget);
  EXPECT_LE(some.kept, all.kept);
  expect_identical(all, some);
  const Solved none = solve_with(h, BackendKind::Embree, 1, 30, false);
  EXPECT_EQ(none.kept_bytes, 0u);
  EXPECT_EQ(none.kept, 0u);
  expect_identical(all, none);
}

}  // namespace
}  // namespace rad
