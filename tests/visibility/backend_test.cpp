// One suite over every backend: blocking, open ends, offsets, batches, concurrency, statistics.
#include "visibility/backend.h"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <random>
#include <vector>

#include "backend_params.h"
#include "core/error.h"
#include "scenegen/scenegen.h"
#include "visibility/triangle_test.h"

namespace rad {
namespace {

ObjectDescription pure(const char* name, std::vector<std::array<Vec3, 3>> tris) {
  ObjectDescription o;
  o.name = name;
  o.kind = ObjectKind::Pure;
  o.material.reflectance = Vec3(0.5f);
  o.triangles = std::move(tris);
  return o;
}

// The square [-r, r]² at height z, front face +z (or -z), cut into n × n cells of two triangles.
std::vector<std::array<Vec3, 3>> square(float z, int n, bool up, float r = 1.0f) {
  std::vector<std::array<Vec3, 3>> t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      float x0 = r * (-1 + 2.0f * i / n), x1 = r * (-1 + 2.0f * (i + 1) / n);
      float y0 = r * (-1 + 2.0f * j / n), y1 = r * (-1 + 2.0f * (j + 1) / n);
      Vec3 a(x0, y0, z), b(x1, y0, z), c(x1, y1, z), d(x0, y1, z);
      if (up) {
        t.push_back({a, b, c});
        t.push_back({a, c, d});
      } else {
        t.push_back({a, c, b});
        t.push_back({a, d, c});
      }
    }
  }
  return t;
}

SceneDescription scene_of(std::vector<ObjectDescription> objects) {
  SceneDescription s;
  s.name = "test";
  for (auto& o : objects) {
    s.roots.push_back(int32_t(s.objects.size()));
    s.objects.push_back(std::move(o));
  }
  return s;
}

class BackendTest : public testing::TestWithParam<BackendParam> {
 protected:
  std::unique_ptr<VisibilityBackend> make(const Hierarchy& h) {
    VisibilityOptions options;
    options.packets = GetParam().packets;
    auto backend = make_visibility_backend(GetParam().kind, h, options);
    EXPECT_EQ(backend->kind(), GetParam().kind);
    return backend;
  }
  std::vector<uint8_t> run(const VisibilityBackend& b, const std::vector<Segment>& segments,
                           VisibilityStats* stats = nullptr) {
    std::vector<uint8_t> out(segments.size(), 7);
    VisibilityStats local;
    b.occluded(segments, out, stats ? *stats : local);
    return out;
  }
  static Segment between(Vec3 a, Vec3 b) { return {a, b - a}; }
};

TEST_P(BackendTest, OccluderBetweenEndpointsBlocks) {
  Hierarchy h = build_hierarchy(scene_of({pure("blocker", square(0.0f, 1, true))}));
  auto b = make(h);
  std::vector<Segment> s = {between({0.2f, 0.3f, -1}, {0.2f, 0.3f, 1}),
                            between({-0.7f, 0.9f, 1}, {0.5f, -0.5f, -2}),
                            between({0.0f, 0.0f, -0.5f}, {3.0f, 3.0f, 0.5f}),  // misses beside
                            between({1.5f, 0.0f, -1}, {1.5f, 0.0f, 1})};
  EXPECT_EQ(run(*b, s), (std::vector<uint8_t>{1, 1, 0, 0}));
}

TEST_P(BackendTest, SegmentEndingJustBeforeTriangleIsNotBlocked) {
  Hierarchy h = build_hierarchy(scene_of({pure("blocker", square(0.0f, 4, true))}));
  auto b = make(h);
  float eps = shadow_offset(h.bounds);
  std::vector<Segment> s = {between({0.2f, 0.3f, -1}, {0.2f, 0.3f, -eps}),
                            between({0.2f, 0.3f, eps}, {0.2f, 0.3f, 1}),
                            between({0.2f, 0.3f, -1}, {0.2f, 0.3f, eps})};
  EXPECT_EQ(run(*b, s), (std::vector<uint8_t>{0, 0, 1}));
}

// Receiver (floor, facing up) and source (ceiling, facing down), finely tessellated: segments
// between their vertices, edge midpoints and interiors, offset by the shared helper, never hit
// their own surfaces; a blocker half-way blocks exactly the segments crossing it.
TEST_P(BackendTest, OwnReceiverAndSourceNotHitThanksToOffsets) {
  for (bool with_blocker : {false, true}) {
    std::vector<ObjectDescription> objects = {pure("floor", square(0.0f, 8, true)),
                                              pure("ceiling", square(1.0f, 8, false))};
    if (with_blocker) objects.push_back(pure("blocker", square(0.5f, 1, true, 0.6f)));
    Hierarchy h = build_hierarchy(scene_of(std::move(objects)));
    auto b = make(h);
    float offset = shadow_offset(h.bounds);
    std::vector<Segment> s;
    for (int i = 0; i <= 16; ++i) {
      for (int j = 0; j <= 16; ++j) {
        Vec3 from(-1 + i / 8.0f, -1 + j / 8.0f, 0.0f);
        Vec3 to(-1 + ((i * 7) % 17) / 8.0f, -1 + ((j * 5) % 17) / 8.0f, 1.0f);
        s.push_back(make_shadow_segment(from, Vec3(0, 0, 1), to, Vec3(0, 0, -1), offset));
      }
    }
    std::vector<uint8_t> out = run(*b, s);
    for (size_t k = 0; k < s.size(); ++k) {
      // The blocker covers [-0.6, 0.6]² at z = 0.5, where the segment's midpoint lies; the
      // midpoints sit on a 1/16 lattice, at least 0.0125 from the blocker's edges.
      Vec3 mid = s[k].origin + 0.5f * s[k].direction;
      bool inside = std::abs(mid.x) < 0.6f && std::abs(mid.y) < 0.6f;
      EXPECT_EQ(out[k], with_blocker && inside ? 1 : 0) << k;
    }
  }
}

TEST_P(BackendTest, EmptyBatch) {
  Hierarchy h = build_hierarchy(scene_of({pure("blocker", square(0.0f, 1, true))}));
  auto b = make(h);
  VisibilityStats stats;
  b->occluded({}, {}, stats);
  EXPECT_EQ(stats.rays, 0u);
  EXPECT_EQ(stats.occluded, 0u);
}

std::vector<Segment> random_segments(const Hierarchy& h, size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Vec3 lo = h.bounds.lo, e = h.bounds.extent();
  std::vector<Segment> s(n);
  for (Segment& seg : s) {
    Vec3 a = lo + e * Vec3(u(rng), u(rng), u(rng));
    Vec3 c = lo + e * Vec3(u(rng), u(rng), u(rng));
    seg = {a, c - a};
  }
  return s;
}

// For every n from 0 to one.size(): trace(n, out, stats) answers the first n queries as `one`
// (their answers one at a time) does, and counts n rays and their blocked ones.
template <typename Trace>
void expect_every_prefix_matches(const std::vector<uint8_t>& one, Trace trace) {
  for (size_t n = 0; n <= one.size(); ++n) {
    VisibilityStats stats;
    std::vector<uint8_t> out;
    trace(n, out, stats);
    EXPECT_EQ(out, std::vector<uint8_t>(one.begin(), one.begin() + n)) << "batch of " << n;
    EXPECT_EQ(stats.rays, n);
    EXPECT_EQ(stats.occluded, size_t(std::count(one.begin(), one.begin() + n, uint8_t{1})));
  }
}

// first_hit: the nearest surface the shared test meets, as brute force over the scene's own
// triangles finds it (the backends trace merged surfaces: the same planes, so the same t and
// the same facing); blocked exactly when occluded() says so.
TEST_P(BackendTest, FirstHitIsTheNearestSurfaceTheSharedTestMeets) {
  Hierarchy h = build_hierarchy(make_triangle_soup(500, 5));
  auto b = make(h);
  const std::vector<TriangleRecord> records = make_triangle_records(h);
  const std::vector<Segment> s = random_segments(h, 400, 13);
  size_t hits = 0;
  for (const Segment& seg : s) {
    SegmentHitRecord best;
    for (uint32_t t = 0; t < records.size(); ++t)
      keep_nearer(best, segment_hit_distance(records[t], seg.origin, seg.direction), t);
    VisibilityStats stats;
    const SegmentHit hit = b->first_hit(seg, stats);
    ASSERT_EQ(hit.hit, best.triangle != ~0u);
    EXPECT_EQ(hit.hit, run(*b, {seg})[0] == 1);
    EXPECT_EQ(stats.rays, 1u);
    if (!hit.hit) continue;
    ++hits;
    EXPECT_NEAR(hit.t, best.t, 1e-5f);
    EXPECT_GT(glm::dot(glm::normalize(hit.normal), h.triangles.normal[best.triangle]), 0.999f);
  }
  EXPECT_GT(hits, 40u);
  EXPECT_LT(hits, s.size());
  // The batch gives the same answers, one by one.
  std::vector<SegmentHit> batch(s.size());
  VisibilityStats stats;
  b->first_hits(s, batch, stats);
  EXPECT_EQ(stats.rays, s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    VisibilityStats one;
    const SegmentHit hit = b->first_hit(s[i], one);
    EXPECT_EQ(batch[i].hit, hit.hit) << i;
    EXPECT_EQ(batch[i].t, hit.t) << i;
    EXPECT_EQ(batch[i].normal, hit.normal) << i;
  }
}

// Two squares stacked, facing each other: the segment through both meets the nearer one,
// whichever way it runs, from behind going up and from behind going down.
TEST_P(BackendTest, FirstHitOfTwoStackedSquaresIsTheNearerOne) {
  Hierarchy h = build_hierarchy(
      scene_of({pure("low", square(0.0f, 3, true)), pure("high", square(1.0f, 3, false))}));
  auto b = make(h);
  VisibilityStats stats;
  const SegmentHit up = b->first_hit(between({0.1f, 0.2f, -1}, {0.1f, 0.2f, 2}), stats);
  ASSERT_TRUE(up.hit);
  EXPECT_NEAR(up.t, 1.0f / 3.0f, 1e-6f);
  EXPECT_GT(up.normal.z, 0.0f);  // the low square's front, met from behind
  const SegmentHit down = b->first_hit(between({0.1f, 0.2f, 2}, {0.1f, 0.2f, -1}), stats);
  ASSERT_TRUE(down.hit);
  EXPECT_NEAR(down.t, 1.0f / 3.0f, 1e-6f);
  EXPECT_LT(down.normal.z, 0.0f);  // the high square's
  EXPECT_FALSE(b->first_hit(between({0.1f, 0.2f, 0.2f}, {0.1f, 0.2f, 0.8f}), stats).hit);
}

TEST_P(BackendTest, BatchSizesOneToFortyMatchOneAtATime) {
  Hierarchy h = build_hierarchy(make_triangle_soup(500, 5));
  auto b = make(h);
  std::vector<Segment> s = random_segments(h, 40, 9);
  // Vertex → samples pattern: half the batch shares an origin.
  for (size_t k = 0; k < 20; ++k) s[k] = {s[0].origin, s[k].origin + s[k].direction - s[0].origin};
  std::vector<uint8_t> one(s.size());
  for (size_t k = 0; k < s.size(); ++k) one[k] = run(*b, {s[k]})[0];
  size_t blocked = 0;
  for (uint8_t o : one) blocked += o;
  EXPECT_GT(blocked, 0u);
  EXPECT_LT(blocked, s.size());
  expect_every_prefix_matches(one, [&](size_t n, std::vector<uint8_t>& out, VisibilityStats& st) {
    out = run(*b, std::vector<Segment>(s.begin(), s.begin() + n), &st);
  });
}

// A fan (one origin, far ends as arrays: the solver's batch) gives exactly the answers of its
// segments one at a time, for every batch size across packet boundaries, and counts them.
TEST_P(BackendTest, FanMatchesItsSegmentsOneAtATime) {
  Hierarchy h = build_hierarchy(make_triangle_soup(500, 5));
  auto b = make(h);
  const std::vector<Segment> s = random_segments(h, 40, 11);
  const Vec3 origin = s[0].origin;
  std::vector<float> x, y, z;
  std::vector<uint8_t> one;
  for (const Segment& seg : s) {
    const Vec3 end = seg.origin + seg.direction;
    x.push_back(end.x), y.push_back(end.y), z.push_back(end.z);
    one.push_back(run(*b, {between(origin, end)})[0]);
  }
  size_t blocked = 0;
  for (uint8_t o : one) blocked += o;
  EXPECT_GT(blocked, 0u);
  EXPECT_LT(blocked, s.size());
  expect_every_prefix_matches(one, [&](size_t n, std::vector<uint8_t>& out, VisibilityStats& st) {
    out.assign(n, 7);
    b->occluded_fan({origin, x.data(), y.data(), z.data(), n}, out, st);
  });
}

TEST_P(BackendTest, ConcurrentCallsFromTbbGiveTheSameAnswers) {
  Hierarchy h = build_hierarchy(make_triangle_soup(2000, 6));
  auto b = make(h);
  std::vector<Segment> s = random_segments(h, 20000, 10);
  std::vector<uint8_t> serial = run(*b, s);
  std::vector<uint8_t> parallel(s.size(), 7);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, s.size(), 37),
                    [&](const tbb::blocked_range<size_t>& r) {
                      VisibilityStats stats;
                      b->occluded(std::span(s).subspan(r.begin(), r.size()),
                                  std::span(parallel).subspan(r.begin(), r.size()), stats);
                    });
  EXPECT_EQ(serial, parallel);
}

TEST_P(BackendTest, StatisticsAddUp) {
  Hierarchy h = build_hierarchy(make_cornell_box(4));
  auto b = make(h);
  std::vector<Segment> s = random_segments(h, 1000, 12);
  VisibilityStats stats;
  stats.rays = 5;  // the call adds to what is there
  std::vector<uint8_t> out = run(*b, s, &stats);
  uint64_t blocked = 0;
  for (uint8_t o : out) blocked += o;
  EXPECT_EQ(stats.rays, 1005u);
  EXPECT_EQ(stats.occluded, blocked);
  if (GetParam().kind == BackendKind::Grid) {
    EXPECT_GE(stats.box_trials, stats.box_hits);
    EXPECT_GT(stats.box_hits, 0u);
    EXPECT_GT(stats.cells_visited, 0u);
    EXPECT_GT(stats.triangle_tests, 0u);
  }
  if (GetParam().kind == BackendKind::Brute) {
    EXPECT_GT(stats.triangle_tests, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(AllBackends, BackendTest, kAllBackends, backend_param_name);

TEST(BackendKind, NamesRoundTrip) {
  for (BackendKind k : {BackendKind::Embree, BackendKind::Grid, BackendKind::Brute}) {
    EXPECT_EQ(parse_backend_kind(to_string(k)), k);
  }
  EXPECT_THROW(parse_backend_kind("bvh"), Error);
}

}  // namespace
}  // namespace rad
