// The Russian roulette over a shot's far receivers (shot_source.h): unbiased on average over the
// shots' draws, and a shot skips what lies beyond its reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/position_bits.h"
#include "scene_builder.h"
#include "solver/gather.h"
#include "solver/shoot.h"
#include "solver/shot_source.h"

namespace rad {
namespace {

// A small light 1 above the origin facing down, and a long floor under it cut into small
// triangles that run out to 40 light widths away.
struct FarFloor {
  Hierarchy h;
  std::unique_ptr<VisibilityBackend> vis;
  SolverState s;
  FarFloor() {
    SceneDescription d;
    testing::add_quad(d, "floor", {-2, -2, 0}, {40, -2, 0}, {40, 2, 0}, {-2, 2, 0}, Vec3(0.5f),
                      Vec3(0), 16);
    testing::add_quad(d, "light", {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                      {0.5f, -0.5f, 1}, Vec3(0), Vec3(1));
    h = build_hierarchy(d);
    vis = make_visibility_backend(BackendKind::Embree, h);
    s = make_solver_state(h, {});
  }
  ShotSource light() const {
    return make_shot_source(s, int32_t(s.scene.clusters.cluster_of[h.triangles.size() - 1]));
  }
};

TEST(Roulette, DrawsLieInTheOpenUnitIntervalAndDependOnTheShotOnly) {
  FarFloor f;
  ShotSource a = f.light(), b = f.light();
  double sum = 0.0;
  for (int64_t shot = 1; shot <= 10000; ++shot) {
    aim_roulette(a, 1e-2f, shot);
    aim_roulette(b, 1e-2f, shot);
    ASSERT_GT(a.roulette_draw, 0.0f);
    ASSERT_LT(a.roulette_draw, 1.0f);
    ASSERT_EQ(a.roulette_draw, b.roulette_draw);
    sum += a.roulette_draw;
  }
  EXPECT_NEAR(sum / 10000.0, 0.5, 0.01);
  // The ends: a draw of 1 would be refused when read back (a checkpoint, another rank).
  EXPECT_GT(open_unit_draw(0), 0.0f);
  EXPECT_LT(open_unit_draw(~uint64_t(0)), 1.0f);
  EXPECT_LT(open_unit_draw(~uint64_t(0) >> 1), open_unit_draw(~uint64_t(0)));
  aim_roulette(a, 0.0f, 7);
  EXPECT_EQ(a.roulette_draw, 0.0f) << "level 0: off";
  EXPECT_EQ(a.roulette_weight(Vec3(1000.0f), Vec3(0, 0, 1), 0.0f), 1.0f);
}

TEST(Roulette, AFarPointsWeightIsOneOnAverageAndNearPointsAlwaysGather) {
  FarFloor f;
  ShotSource src = f.light();
  // Unit unshot radiosity, area 1: the gain bound at distance d is 1 / (pi d^2). A level that
  // puts the reach at distance 2.
  const float level = 1.0f / (std::numbers::pi_v<float> * 4.0f);
  // 1.5 and sqrt(40) straight below the light, facing it: both cosines 1.
  const Vec3 near(0.5f, 0.5f, -0.5f), far(0.5f, 0.5f, 1.0f - 2.0f * std::sqrt(10.0f));
  const Vec3 up(0.0f, 0.0f, 1.0f);
  double sum = 0.0;
  int gathered = 0;
  const int draws = 100000;
  for (int64_t shot = 1; shot <= draws; ++shot) {
    aim_roulette(src, level, shot);
    ASSERT_EQ(src.roulette_weight(near, up, 0.0f), 1.0f);
    const float w = src.roulette_weight(far, up, 0.0f);
    sum += w;
    gathered += w > 0.0f;
  }
  // q = (2 / d)^2 = 0.1 at the far point: a tenth of the draws gather, each with weight 10.
  EXPECT_NEAR(double(gathered) / draws, 0.1, 0.005);
  EXPECT_NEAR(sum / draws, 1.0, 0.04);
}

TEST(Roulette, LotZeroDrawsTheShotsDrawAndTheLeastDrawIsTheLeastLots) {
  FarFloor f;
  ShotSource src = f.light();
  for (int64_t shot = 1; shot <= 10000; ++shot) {
    aim_roulette(src, 1e-2f, shot);
    ASSERT_EQ(src.lot_draw(0), src.roulette_draw);
    float least = 1.0f;
    for (uint32_t k = 0; k < ShotSource::kRouletteLots; ++k) {
      const float d = src.lot_draw(k);
      ASSERT_GT(d, 0.0f);
      ASSERT_LT(d, 1.0f);
      // k / kRouletteLots apart, modulo 1, to the bit (in double, where the sum is exact).
      const double shifted = double(src.roulette_draw) + double(k) / ShotSource::kRouletteLots;
      ASSERT_EQ(double(d), std::fmod(shifted, 1.0)) << "shot " << shot << " lot " << k;
      least = std::min(least, d);
    }
    ASSERT_EQ(src.least_draw(1.0f), least);
    ASSERT_EQ(src.least_draw(ShotSource::kLotsFromQ), least);
    ASSERT_EQ(src.least_draw(0.5f * ShotSource::kLotsFromQ), src.roulette_draw);
  }
  // -0 and +0 are one position: a vertex draws the same whichever polygon's copy asks.
  aim_roulette(src, 1e-2f, 3);
  for (int i = 0; i < 64; ++i) {
    const Vec3 a(0.0f, float(i), 0.0f), b(-0.0f, float(i), -0.0f);
    ASSERT_EQ(position_seed(a), position_seed(b));
    ASSERT_EQ(src.point_draw(a, 0.5f), src.point_draw(b, 0.5f));
  }
}

TEST(Roulette, OfManyPointsOfOneQAShotGathersOneLotOrNone) {
  // 2,000 points straight below the light (its box), facing it: one q, between kLotsFromQ and
  // 1 / kRouletteLots. One draw per shot would have them all gather, or none; the lots have a
  // shot gather about a quarter of them, or none, and each point gathers with probability q
  // over the shots.
  FarFloor f;
  ShotSource src = f.light();
  const float level = 1.0f / (std::numbers::pi_v<float> * 4.0f);  // reach 2, as above
  const float depth = 1.0f - 2.0f * std::sqrt(10.0f);             // q = 0.1
  std::vector<Vec3> points;
  for (int i = 0; i < 2000; ++i) points.push_back(Vec3(-0.45f + 4.5e-4f * float(i), 0.5f, depth));
  const Vec3 up(0.0f, 0.0f, 1.0f);
  ASSERT_GE(0.1f, ShotSource::kLotsFromQ);
  ASSERT_LT(0.1f, 1.0f / float(ShotSource::kRouletteLots));
  std::vector<int> gathered(points.size(), 0);
  int shots_gathering = 0;
  const int shots = 20000;
  for (int64_t shot = 1; shot <= shots; ++shot) {
    aim_roulette(src, level, shot);
    size_t n = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      const float w = src.roulette_weight(points[i], up, 0.0f);
      if (w > 0.0f) {
        ASSERT_NEAR(w, 10.0f, 0.05f);
        ++gathered[i], ++n;
      }
    }
    if (n == 0) continue;
    ++shots_gathering;
    // One lot of four: binomial about 500 of 2,000 (standard deviation 19), well within 400..600.
    ASSERT_GT(n, 400u) << "shot " << shot;
    ASSERT_LT(n, 600u) << "shot " << shot;
  }
  // A shot gathers some lot with probability 4q = 0.4.
  EXPECT_NEAR(double(shots_gathering) / shots, 0.4, 0.02);
  double mean = 0.0;
  for (int g : gathered) mean += double(g) / shots / double(points.size());
  EXPECT_NEAR(mean, 0.1, 0.005);
  // Each point alone gathers with probability q too.
  for (int g : gathered) ASSERT_NEAR(double(g) / shots, 0.1, 0.02);
}

TEST(Roulette, APointsGainIsAtMostTheLevelTimesItsQ) {
  // q bounds the gain by the distance and both cosines (roulette_q): were a bound wrong, a
  // point would gather more than the level at once, or be skipped where it gains.
  FarFloor f;
  const ShotSource plain = f.light();
  const GatherSettings g = gather_settings(f.s);
  ShotSource src = plain;
  // The reach on distance alone at 2.5: the cosines bound the points beyond.
  const float level = 0.05f;
  aim_roulette(src, level, 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-20.0f, 20.0f), z(0.05f, 0.95f), c(-1.0f, 1.0f);
  GatherScratch sc;
  int bounded = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 x(u(rng), u(rng), z(rng));
    const Vec3 n = glm::normalize(Vec3(c(rng), c(rng), c(rng)) + Vec3(0.0f, 0.0f, 1e-3f));
    const float gain = gather_from_source(x, n, x, plain, *f.vis, g, sc).x;
    const float q = src.roulette_q(distance2(src.box, x), src.height(x), src.facing(x, n));
    if (q >= 1.0f) continue;
    ++bounded;
    ASSERT_LE(gain, level * q * 1.02f + 1e-9f) << "at " << x.x << " " << x.y << " " << x.z;
    if (q == 0.0f) {
      EXPECT_EQ(gain, 0.0f);
    }
  }
  EXPECT_GT(bounded, 3000);
}

TEST(Roulette, ABoxBeyondReachHoldsNoPointThatGathers) {
  FarFloor f;
  ShotSource src = f.light();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-30.0f, 30.0f), size(0.0f, 5.0f), c(-1.0f, 1.0f);
  int beyond = 0, within = 0;
  for (int i = 0; i < 2000; ++i) {
    aim_roulette(src, 1e-3f, i + 1);
    Aabb box;
    box.extend(Vec3(u(rng), u(rng), u(rng)));
    box.extend(box.lo + Vec3(size(rng), size(rng), size(rng)));
    const bool reaches = src.roulette_reaches_box(box);
    (reaches ? within : beyond) += 1;
    for (int k = 0; k < 8; ++k) {
      const Vec3 t(float(k & 1), float((k >> 1) & 1), float((k >> 2) & 1));
      const Vec3 x = box.lo + (box.hi - box.lo) * t;
      const Vec3 n = glm::normalize(Vec3(c(rng), c(rng), c(rng)) + Vec3(0.0f, 0.0f, 1e-3f));
      // Whatever its normal, within the slack of a point inside its triangle.
      const float slack = kRouletteSlack * glm::length(box.extent());
      if (!reaches) {
        EXPECT_EQ(src.roulette_weight(x, n, slack), 0.0f);
      }
      // A point that gathers lies in a triangle the shot reaches (the test bounds every lot's
      // draw, so it may reach a point whose own lot does not gather).
      Aabb point;
      point.extend(x);
      if (src.roulette_weight(x, n, 0.0f) > 0.0f) {
        EXPECT_TRUE(src.roulette_reaches_triangle(point, x, n));
      }
    }
  }
  EXPECT_GT(beyond, 100);
  EXPECT_GT(within, 100);
}

TEST(Roulette, TheFloorGainsTheSameOnAverageAndAShotSkipsWhatItDoesNotReach) {
  FarFloor f;
  const ShotSource plain = f.light();
  const GatherSettings g = gather_settings(f.s);
  const size_t floor_triangles = f.h.triangles.size() - 2;
  // The gain of the floor beyond x = 3 (where the roulette plays) summed over its vertices, each
  // weighted by its triangle's area: without the roulette, and on average over shots with it.
  auto floor_gain = [&](const ShotSource& src) {
    GatherScratch sc;
    double sum = 0.0;
    for (size_t p = 0; p < floor_triangles; ++p) {
      for (const Vec3& x : f.h.triangles.corners[p]) {
        if (x.x <= 3.0f) continue;
        sum += double(f.h.triangles.area[p]) * gather_from_source(x, f.h.triangles.normal[p],
                                                                  f.h.triangles.centroid(p), src,
                                                                  *f.vis, g, sc)
                                                   .x;
      }
    }
    return sum;
  };
  const double exact = floor_gain(plain);
  // The level where the reach is 3: the floor runs to 40.
  const float level = 1.0f / (std::numbers::pi_v<float> * 9.0f);
  double mean = 0.0;
  const int shots = 30000;
  for (int64_t shot = 1; shot <= shots; ++shot) {
    ShotSource src = plain;
    aim_roulette(src, level, shot);
    mean += floor_gain(src) / shots;
  }
  std::printf("far floor gain: %.6f without the roulette, %.6f on average with it\n", exact, mean);
  // 5%: the mean of 30,000 draws (over other runs of 30,000 its spread is about 2%, the gain
  // being mostly that of rare far points with large weights); without the division by q it
  // comes out 90% short.
  EXPECT_NEAR(mean, exact, 0.05 * exact);

  // One shot: its receivers are the floor triangles whose box it reaches, and the others keep
  // nothing of it.
  ShotSource src = plain;
  int64_t shot = 1;
  // A shot whose lots all draw high: the least of them (least_draw) at least 0.2.
  for (aim_roulette(src, level, shot); src.least_draw(1.0f) < 0.2f;
       aim_roulette(src, level, ++shot)) {
  }
  shoot_to_receivers({f.s.options, f.s.scene, f.s.energy, f.s.shots, f.s.ownership, f.s.solution,
                      f.s.receivers, f.s.kept, f.s.stats},
                     src, *f.vis, false);
  size_t reached = 0;
  for (size_t p = 0; p < floor_triangles; ++p) {
    Aabb b;
    for (const Vec3& x : f.h.triangles.corners[p]) b.extend(x);
    const bool reaches =
        src.roulette_reaches_triangle(b, f.h.triangles.corners[p][0], f.h.triangles.normal[p]);
    reached += reaches;
    EXPECT_EQ(bool(f.s.receivers.marked[p]), reaches) << "triangle " << p;
  }
  EXPECT_GT(reached, 0u);
  EXPECT_LT(reached, floor_triangles / 4);
}

}  // namespace
}  // namespace rad
