// Segment–triangle test of design §6: inside, edges, vertices, open ends, grazing, degenerate.
#include "visibility/triangle_test.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <random>
#include <vector>

namespace rad {
namespace {

// a = (1,0,0), b = (0,1,0), c = 0: every quantity below is exact in float.
TriangleRecord unit_triangle() {
  return make_triangle_record({Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0)});
}

bool hits_vertical(const TriangleRecord& r, float x, float y) {
  return segment_hits_triangle(r, Vec3(x, y, -1), Vec3(0, 0, 2));
}

TEST(SegmentHitsTriangle, RecordMatchesSpecFormulas) {
  TriangleRecord r = unit_triangle();
  EXPECT_EQ(r.normal, Vec3(0, 0, 1));
  EXPECT_EQ(r.s_a, Vec3(1, 0, 0));
  EXPECT_EQ(r.s_b, Vec3(0, 1, 0));
  EXPECT_EQ(r.plane_offset, 0.0f);
}

TEST(SegmentHitsTriangle, HitsInsideMissesOutside) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(hits_vertical(r, 0.25f, 0.25f));
  EXPECT_FALSE(hits_vertical(r, 0.75f, 0.75f));
  EXPECT_FALSE(hits_vertical(r, -0.1f, 0.5f));
  EXPECT_FALSE(hits_vertical(r, 0.5f, -0.1f));
}

TEST(SegmentHitsTriangle, EdgesAndVerticesCount) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5f));  // hypotenuse: α + β = 1
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.0f));  // β = 0
  EXPECT_TRUE(hits_vertical(r, 0.0f, 0.5f));  // α = 0
  EXPECT_TRUE(hits_vertical(r, 0.0f, 0.0f));  // c
  EXPECT_TRUE(hits_vertical(r, 1.0f, 0.0f));  // a
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5f + 1e-6f) == false);
  EXPECT_FALSE(hits_vertical(r, -1e-6f, 0.5f));
}

TEST(SegmentHitsTriangle, BothSidesBlock) {
  TriangleRecord r = unit_triangle();
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, 1), Vec3(0, 0, -2)));
}

TEST(SegmentHitsTriangle, EndsAreOpen) {
  TriangleRecord r = unit_triangle();
  // Starting on the plane (t = 0), ending on it (t = 1), or stopping short: no hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, 0), Vec3(0, 0, 1)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 1)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 0.999f)));
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(0.2f, 0.2f, -1), Vec3(0, 0, 1.001f)));
}

TEST(SegmentHitsTriangle, GrazingSegments) {
  TriangleRecord r = unit_triangle();
  // In the plane: parallel, never a hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, 0), Vec3(3, 0, 0)));
  // Parallel just above: no hit.
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, 1e-6f), Vec3(3, 0, 0)));
  // Crossing the plane at a shallow angle inside the triangle: hit; outside: miss.
  EXPECT_TRUE(segment_hits_triangle(r, Vec3(-1, 0.2f, -1e-3f), Vec3(2.6f, 0, 2e-3f)));
  EXPECT_FALSE(segment_hits_triangle(r, Vec3(-1, 0.2f, -1e-3f), Vec3(0.8f, 0, 2e-3f)));
}

TEST(SegmentHitsTriangle, DegenerateNeverHits) {
  // Collinear corners: zero record.
  TriangleRecord line = make_triangle_record({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)});
  EXPECT_EQ(line.normal, Vec3(0.0f));
  EXPECT_FALSE(segment_hits_triangle(line, Vec3(1, 1, -1), Vec3(0, 0, 2)));
  TriangleRecord point = make_triangle_record({Vec3(1), Vec3(1), Vec3(1)});
  EXPECT_FALSE(segment_hits_triangle(point, Vec3(1, 1, 0), Vec3(0, 0, 2)));
  // A zero-length segment never hits.
  EXPECT_FALSE(segment_hits_triangle(unit_triangle(), Vec3(0.2f, 0.2f, 0), Vec3(0)));
}

TEST(SegmentHitsTriangle, ThinTriangleStillHit) {
  TriangleRecord r = make_triangle_record({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5f, 1e-3f, 0)});
  EXPECT_TRUE(hits_vertical(r, 0.5f, 0.5e-3f));
  EXPECT_FALSE(hits_vertical(r, 0.5f, 2e-3f));
}

// The packet form answers lane by lane what the one-triangle form does, bit for bit: random
// triangles (some tiny, some degenerate) and segments through their edges and corners, or ending
// on their planes, so that many answers hang on the last bit of t, α or β.
TEST(SegmentHitsPacket, EveryLaneAnswersAsTheOneTriangleTest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
  auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  std::vector<std::array<Vec3, 3>> corners;
  for (int i = 0; i < 64; ++i) {
    Vec3 a = point(), b = point(), c = point();
    if (i % 8 == 3) c = a + 1e-4f * (b - a);                           // nearly collinear
    if (i % 8 == 5) b = a + 1e-5f * point(), c = a + 1e-5f * point();  // tiny
    if (i % 8 == 7) c = b;                                             // degenerate
    corners.push_back({a, b, c});
  }
  std::vector<TriangleRecord> records;
  for (const auto& t : corners) records.push_back(make_triangle_record(t));
  constexpr uint32_t kUsed = 6;  // the last two lanes stay empty
  int hits = 0, misses = 0;
  for (size_t first = 0; first < records.size(); first += TrianglePacket::kLanes) {
    TrianglePacket packet;
    for (uint32_t lane = 0; lane < kUsed; ++lane) packet.set(lane, records[first + lane]);
    for (int s = 0; s < 4000; ++s) {
      const size_t target = first + uint32_t(s) % kUsed;
      const auto& [a, b, c] = corners[target];
      Vec3 origin = point(), end = point();
      switch (s % 4) {
        case 0: {  // through a point of an edge or a corner: α, β or α + β within rounding
          const Vec3 ends[3][2] = {{c, b}, {c, a}, {a, b}};
          const int edge = (s / 4) % 3;
          const Vec3 on = glm::mix(ends[edge][0], ends[edge][1], (s / 12) % 5 ? unit(rng) : 0.0f);
          end = origin + 2.0f * (on - origin);
          break;
        }
        case 1: {  // ending on the plane: t = 1 within rounding
          const TriangleRecord& r = records[target];
          const float n2 = glm::dot(r.normal, r.normal);
          if (n2 > 0.0f) end -= r.normal * ((glm::dot(r.normal, end) - r.plane_offset) / n2);
          break;
        }
        case 2:  // starting on a corner: t = 0 within rounding
          origin = c;
          break;
        default:
          break;
      }
      const Vec3 direction = end - origin;
      uint32_t expected = 0;
      for (uint32_t lane = 0; lane < kUsed; ++lane) {
        expected |= uint32_t(segment_hits_triangle(records[first + lane], origin, direction))
                    << lane;
      }
      ASSERT_EQ(segment_hits_packet(packet, origin, direction), expected) << first << " " << s;
      hits += std::popcount(expected);
      misses += int(kUsed) - std::popcount(expected);
    }
  }
  EXPECT_GT(hits, 1000);  // the comparison covered hits as well as misses
  EXPECT_GT(misses, 1000);
}

}  // namespace
}  // namespace rad
