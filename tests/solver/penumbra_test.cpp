// Penumbra rays (SolverOptions::penumbra_rays): where a point's shadow rays to a lamp disagree,
// more rays to points of the strata that differ from point to point bring the penumbra's
// direct light close to the exact one, without the steps of the 16 fixed ends; points that see
// all of the lamp or none of it cast no more rays.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene_builder.h"
#include "solver/gather.h"
#include "solver/shoot.h"
#include "umbra_scene.h"

namespace rad {
namespace {

using testing::exact_direct;
using testing::kBlockerHalf;
using testing::kLampEmission;
using testing::kLampHalf;
using testing::kLampHeight;
using testing::rectangle_factor;
using testing::umbra_scene;

struct Umbra {
  Hierarchy h = build_hierarchy(umbra_scene());
  std::unique_ptr<VisibilityBackend> vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  // The lamp's first shot: all the emitted energy, major as the solver makes it.
  ShotSource lamp() const {
    ShotSource src = make_shot_source(s, int32_t(s.scene.clusters.cluster_of[6]));
    src.major = true;
    return src;
  }
  // The gain at floor point (x, 0, z) with `rays` penumbra rays, and the shadow rays it cast.
  float gain(const ShotSource& src, float x, float z, int rays, uint64_t* cast = nullptr) const {
    GatherSettings g = gather_settings(s);
    g.penumbra_rays = uint32_t(rays);
    GatherScratch sc;
    const float gain =
        gather_from_source({x, 0.0f, z}, {0, 1, 0}, h.triangles.centroid(0), src, *vis, g, sc).x;
    if (cast) *cast = sc.stats.rays.rays;
    return gain;
  }
};

TEST(Penumbra, MoreRaysWhereTheyDisagreeBringTheDirectLightToTheExactOne) {
  const Umbra u;
  const ShotSource src = u.lamp();
  ASSERT_EQ(src.sample_count, 16u);
  const double open =
      kLampEmission * rectangle_factor(-kLampHalf, kLampHalf, -kLampHalf, kLampHalf, kLampHeight);
  // Across the penumbra (x from 0.85 to 1.15 at z = 0.05), the mean error relative to the
  // unshadowed light.
  double error_off = 0.0, error_on = 0.0;
  int points = 0;
  for (int i = 0; i <= 120; ++i) {
    const float x = 0.82f + 0.36f * float(i) / 120.0f, z = 0.05f;
    const double exact = exact_direct(x, z);
    error_off += std::abs(u.gain(src, x, z, 0) - exact);
    error_on += std::abs(u.gain(src, x, z, 8) - exact);
    ++points;
  }
  error_off /= points * open;
  error_on /= points * open;
  RecordProperty("error_off", std::to_string(error_off));
  RecordProperty("error_on", std::to_string(error_on));
  EXPECT_LT(error_on, 0.015) << "without: " << error_off;
  EXPECT_LT(error_on, 0.5 * error_off);
}

TEST(Penumbra, PointsThatSeeAllOfTheLampOrNoneCastOnlyTheCornerProbes) {
  const Umbra u;
  const ShotSource src = u.lamp();
  // Umbra and lit floor, clear of the penumbra (0.85 to 1.15): the same gain, with at most
  // one ray more per corner of the lamp.
  for (const float x : {0.0f, 0.5f, 1.5f, 1.9f}) {
    uint64_t off = 0, on = 0;
    const float a = u.gain(src, x, 0.05f, 0, &off), b = u.gain(src, x, 0.05f, 8, &on);
    EXPECT_EQ(a, b) << x;
    EXPECT_GT(off, 0u) << x;
    EXPECT_LE(on, off + 4) << x;
  }
  // In the penumbra the rounds cast 8 more rays per sample, the same on every call.
  uint64_t off = 0, on = 0;
  u.gain(src, 1.0f, 0.05f, 0, &off);
  const float b = u.gain(src, 1.0f, 0.05f, 8, &on);
  EXPECT_EQ(on, 9 * off);
  EXPECT_EQ(b, u.gain(src, 1.0f, 0.05f, 8));
}

TEST(Penumbra, NearThePenumbrasEdgesTheCornersSeeWhatTheSamplesMiss) {
  // Just inside the umbra's edge (0.85) and the penumbra's outer edge (1.15), every sample's
  // ray agrees, yet a sliver of the lamp shows or hides: the corners' rays find it.
  const Umbra u;
  const ShotSource src = u.lamp();
  for (const float x : {0.86f, 1.14f}) {
    const double exact = exact_direct(x, 0.0);
    const double off = std::abs(u.gain(src, x, 0.0f, 0) - exact);
    const double on = std::abs(u.gain(src, x, 0.0f, 8) - exact);
    EXPECT_LT(on, off) << x;
  }
}

TEST(Penumbra, AMinorShotGetsNoRounds) {
  const Umbra u;
  ShotSource src = u.lamp();
  src.major = false;
  uint64_t off = 0, on = 0;
  EXPECT_EQ(u.gain(src, 1.0f, 0.05f, 0, &off), u.gain(src, 1.0f, 0.05f, 8, &on));
  EXPECT_EQ(off, on);
}

}  // namespace
}  // namespace rad
