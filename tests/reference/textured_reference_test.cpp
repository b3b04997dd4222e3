// The reference path tracer sees what rad sees on textured and cut-out surfaces: a floor
// textured by a checker reads as the floor cut into its squares, and a leaf cut out by a mask
// as the leaf's opaque half alone (the scenes of tools/scenegen/model_pairs.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "reference/path_tracer.h"
#include "scenegen/model_pairs.h"

namespace rad {
namespace {

// The reference point at `x` on the triangle of a Pure whose name starts with `prefix` that
// holds it (facing up or down, as the floor and the leaf do).
ReferencePoint point_at(const Hierarchy& h, const std::string& prefix, const Vec3& x) {
  const Triangles& t = h.triangles;
  for (size_t i = 0; i < t.size(); ++i) {
    if (h.objects[size_t(t.object[i])].name.rfind(prefix, 0) != 0) continue;
    const auto& c = t.corners[i];
    const Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    if (std::abs(glm::dot(x - c[0], n)) > 1e-6f * glm::length(n)) continue;
    const float nn = glm::dot(n, n);
    const float u = glm::dot(glm::cross(x - c[0], c[2] - c[0]), n) / nn;
    const float v = glm::dot(glm::cross(c[1] - c[0], x - c[0]), n) / nn;
    if (u < 0.0f || v < 0.0f || u + v > 1.0f) continue;
    return {int32_t(i), u, v, x, t.normal[i]};
  }
  ADD_FAILURE() << "no triangle of " << prefix << " holds the point";
  return {};
}

// Points at the same places of two scenes: on the Pures named from prefix_a in a and prefix_b in
// b.
struct PointPairs {
  const Hierarchy &a, &b;
  std::vector<ReferencePoint> in_a = {}, in_b = {};
  void add(const std::string& prefix_a, const std::string& prefix_b, const Vec3& x) {
    in_a.push_back(point_at(a, prefix_a, x));
    in_b.push_back(point_at(b, prefix_b, x));
  }
};

// Each point's radiosity in the two scenes, agreeing within five combined standard errors in
// every channel; returns scene a's.
std::vector<ReferenceValue> expect_same(const PointPairs& p) {
  TraceOptions to;
  to.target_stderr = 0.01;
  const std::vector<ReferenceValue> va = estimate_radiosity(p.a, p.in_a, to);
  const std::vector<ReferenceValue> vb = estimate_radiosity(p.b, p.in_b, to);
  for (size_t i = 0; i < va.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = va[i].radiosity[c] - vb[i].radiosity[c];
      const double se = std::hypot(va[i].standard_error[c], vb[i].standard_error[c]);
      EXPECT_LE(std::abs(d), 5.0 * se + 1e-9)
          << "point " << i << " channel " << c << ": " << va[i].radiosity[c] << " against "
          << vb[i].radiosity[c];
    }
  }
  return va;
}

TEST(ReferenceTextures, ATexturedFloorReadsAsTheFloorCutIntoItsSquares) {
  const auto checker = checker_texture();
  const Hierarchy textured = build_hierarchy(checker_room(checker, true));
  const Hierarchy squares = build_hierarchy(checker_room(checker, false));
  // Inside every square (not on a square's edge, where NEAREST picks a side), and two points of
  // the ceiling, lit by the floor's light.
  PointPairs p{textured, squares};
  for (int i = 0; i < kCheckerSquares; ++i) {
    for (int j = 0; j < kCheckerSquares; ++j) {
      const Vec3 x((float(i) + 0.3f) / kCheckerSquares, 0.0f, (float(j) + 0.6f) / kCheckerSquares);
      p.add("floor", "floor " + std::to_string(i) + " " + std::to_string(j), x);
    }
  }
  for (const Vec3& x : {Vec3(0.15f, 1.0f, 0.2f), Vec3(0.85f, 1.0f, 0.7f)}) {
    p.add("ceiling", "ceiling", x);
  }
  const std::vector<ReferenceValue> v = expect_same(p);
  // The light and dark squares differ: the texture is read, not its mean.
  EXPECT_GT(v[0].radiosity.x, 2.0 * v[1].radiosity.x);
}

TEST(ReferenceTextures, AnEmissiveTextureLightsAsTheFloorCutIntoItsSquares) {
  const auto checker = checker_texture();
  const Hierarchy textured = build_hierarchy(checker_lit_room(checker, true));
  const Hierarchy squares = build_hierarchy(checker_lit_room(checker, false));
  // The wall x = 0 just above the floor, beside each square of the first column: lit mostly by
  // that square.
  PointPairs p{textured, squares};
  for (int j = 0; j < kCheckerSquares; ++j) {
    p.add("x0", "x0", Vec3(0.0f, 0.02f, (float(j) + 0.5f) / kCheckerSquares));
  }
  const std::vector<ReferenceValue> v = expect_same(p);
  EXPECT_GT(v[0].radiosity.x, 2.0 * v[1].radiosity.x);
}

TEST(ReferenceTextures, RaysPassACutOutsHoles) {
  const Hierarchy cut = build_hierarchy(cutout_room(true));
  const Hierarchy half = build_hierarchy(cutout_room(false));
  // The floor under the leaf's opaque half and under its hole, and the opaque half itself.
  PointPairs p{cut, half};
  for (float x : {0.3f, 0.4f, 0.6f, 0.7f}) {
    for (float z : {0.3f, 0.6f}) p.add("floor", "floor", Vec3(x, 0.0f, z));
  }
  p.add("leaf", "leaf", Vec3(0.3f, 0.5f, 0.4f));
  const std::vector<ReferenceValue> v = expect_same(p);
  // The opaque half shades the floor under it; the hole lets the lamp through.
  EXPECT_LT(v[0].radiosity.y, v[4].radiosity.y);
}

}  // namespace
}  // namespace rad
