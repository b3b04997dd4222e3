// The vertex-to-source gather: the corner trap and the intensity cut.
#include "solver/gather.h"

#include <gtest/gtest.h>

#include "scene_builder.h"
#include "solver/form_factor.h"
#include "solver/shoot.h"

namespace rad {
namespace {

// A floor and an emitting wall meeting along x = 0. A floor vertex on that line sees the wall
// edge-on: EQ 7 at the vertex itself gives 0, while just beside it the wall fills a quarter of
// the view (F -> 1/4 at the wall's corner, 1/2 along its middle).
struct CornerScene {
  Hierarchy h;
  std::unique_ptr<VisibilityBackend> vis;
  SolverState s;
  CornerScene() {
    SceneDescription d;
    testing::add_quad(d, "floor", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Vec3(0.5f), Vec3(0));
    testing::add_quad(d, "wall", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, Vec3(0), Vec3(1));
    h = build_hierarchy(d);
    vis = make_visibility_backend(BackendKind::Embree, h);
    s = make_solver_state(h, {});
  }
  // Gain at floor point x from both wall triangles.
  float gain(Vec3 x, GatherSettings g) {
    GatherScratch sc;
    float sum = 0;
    for (int32_t src = 2; src < 4; ++src) {
      sum += gather_from_source(x, {0, 0, 1}, polygon_centroid(h.triangles, 1), 
                                make_shot_source(s, src), *vis, g, sc).x;
    }
    return sum;
  }
};

TEST(Gather, VertexOnTheLineWhereTwoSurfacesMeetGetsTheLimitFromInside) {
  CornerScene c;
  const Vec3 on_line(0, 0.5f, 0);
  GatherSettings g = gather_settings(c.s);
  // Reference: the exact form factor a little inside the floor.
  const float inside = point_to_triangle_form_factor({1e-3f, 0.5f, 0}, {0, 0, 1}, {0, 0, 0},
                                                     {0, 1, 0}, {0, 1, 1}) +
                       point_to_triangle_form_factor({1e-3f, 0.5f, 0}, {0, 0, 1}, {0, 0, 0},
                                                     {0, 1, 1}, {0, 0, 1});
  ASSERT_GT(inside, 0.3f);
  const float with_inset = c.gain(on_line, g);
  g.inset = 0;
  const float without_inset = c.gain(on_line, g);
  g.method = FormFactorMethod::Samples;
  const float original = c.gain(on_line, g);
  std::printf("on the wall/floor line: exact %.4f, rad %.4f, no inset %.4f, original EQ 7 %.4f\n",
              inside, with_inset, without_inset, original);
  EXPECT_NEAR(with_inset, inside, 0.01f * inside);
  EXPECT_LT(without_inset, 0.05f * inside) << "the trap: edge-on, nothing gathered";
  EXPECT_LT(original, 0.05f * inside);
}

TEST(Gather, IntensityCutSkipsRaysAndCountsThem) {
  CornerScene c;
  GatherSettings g = gather_settings(c.s);
  GatherScratch sc;
  const ShotSource src = make_shot_source(c.s, 2);
  const Vec3 x(0.7f, 0.5f, 0);
  const Vec3 traced = gather_from_source(x, {0, 0, 1}, x, src, *c.vis, g, sc);
  EXPECT_EQ(sc.stats.intensity_cuts, 0u);
  EXPECT_GT(sc.stats.rays.rays, 0u);
  g.cut = 1e9f;
  const uint64_t rays_before = sc.stats.rays.rays;
  const Vec3 cut = gather_from_source(x, {0, 0, 1}, x, src, *c.vis, g, sc);
  EXPECT_EQ(sc.stats.rays.rays, rays_before) << "no shadow ray below the cut";
  EXPECT_GT(sc.stats.intensity_cuts, 0u);
  EXPECT_FLOAT_EQ(cut.x, traced.x) << "nothing blocks here, so the unoccluded gain is exact";
}

}  // namespace
}  // namespace rad
