// A textured surface reflects per vertex: its texture filtered over the element the vertex
// stands for. A checker-textured floor solves as the same floor cut into coloured squares.
#include "solver/texture_factors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "hierarchy/auto_hierarchy.h"
#include "scene_builder.h"
#include "visibility/backend.h"

namespace rad {
namespace {

using testing::solve_shots;

constexpr int kSquares = kCheckerSquares, kTexels = kCheckerTexels;

// A vertex value (radiosity, or irradiance when `arriving`) integrated over the leaves of the
// polygons `pick` selects, into the bin of each leaf's centroid.
template <typename Pick, typename Bin>
std::vector<DVec3> integrate(const SolverState& s, Pick pick, Bin bin, size_t bins,
                             bool arriving = false) {
  std::vector<DVec3> sum(bins, DVec3(0.0));
  const Solution& sol = s.solution;
  for (size_t p = 0; p < sol.mesh.polygons.size(); ++p) {
    if (!pick(p)) continue;
    const PolygonMesh& m = sol.mesh.polygons[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      const Vec3 c = (m.positions[el.v[0]] + m.positions[el.v[1]] + m.positions[el.v[2]]) / 3.0f;
      auto value = [&](uint32_t v) {
        return arriving ? sol.vertex_states[p][v].irradiance : sol.radiosity(p, v);
      };
      const Vec3 b = value(el.v[0]) + value(el.v[1]) + value(el.v[2]);
      sum[bin(c)] += DVec3(b) * (double(el.area) / 3.0);
    });
  }
  return sum;
}

TEST(TextureFactors, AVertexReadsItsTexelWhenSmallAndTheMeanWhenItCoversTheImage) {
  const auto checker = checker_texture();
  ASSERT_TRUE(checker);
  const SceneDescription d = checker_room(checker, true);
  const Hierarchy h = build_hierarchy(d);
  const size_t floor = h.triangles.size() - 2;
  ASSERT_TRUE(is_textured(h.triangles, floor, h.objects.back()));
  ASSERT_FALSE(is_textured(h.triangles, 0, h.objects.front()));
  const SceneObject& t = h.objects.back();
  // The middle of square (0, 0), light; of square (1, 0), dark. A tiny element reads the texel.
  const Vec3 light = texture_factor(h.triangles, floor, t, {0.125f, 0, 0.125f}, 1e-6f).reflectance;
  const Vec3 dark = texture_factor(h.triangles, floor, t, {0.375f, 0, 0.125f}, 1e-6f).reflectance;
  const Vec4 texel_light = checker->levels[0].texels[8 * kTexels + 8];
  EXPECT_NEAR(light.x * checker->mean.x, texel_light.x, 1e-5f);
  EXPECT_GT(light.x, 1.0f);
  EXPECT_LT(dark.x, 1.0f);
  // An element as large as the floor: the whole checker's mean, a factor of 1.
  const Vec3 whole = texture_factor(h.triangles, floor, t, {0.5f, 0, 0.5f}, 1.0f).reflectance;
  EXPECT_NEAR(whole.x, 1.0f, 1e-3f);
  EXPECT_NEAR(whole.z, 1.0f, 1e-3f);
}

TEST(TextureFactors, RegroupingKeepsTheTexturesAndTheirCoordinates) {
  const auto checker = checker_texture();
  const Hierarchy h = build_hierarchy(checker_room(checker, true));
  for (const HierarchyMode mode : {HierarchyMode::Automatic, HierarchyMode::Flat}) {
    const Hierarchy r = regrouped_hierarchy(h, mode);
    ASSERT_EQ(r.triangles.uv.size(), r.triangles.size()) << to_string(mode);
    size_t textured = 0;
    for (size_t t = 0; t < r.triangles.size(); ++t) {
      const SceneObject& m = r.objects[size_t(r.triangles.object[t])];
      if (!is_textured(r.triangles, t, m)) continue;
      ++textured;
      // The coordinates are the floor's: u = x, v = z at every corner.
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(r.triangles.uv[t][size_t(k)],
                  Vec2(r.triangles.corners[t][size_t(k)].x, r.triangles.corners[t][size_t(k)].z));
      }
    }
    EXPECT_EQ(textured, 2u) << to_string(mode);
  }
}

TEST(TextureFactors, ACheckerFloorSolvesAsTheFloorCutIntoColouredSquares) {
  const auto checker = checker_texture();
  ASSERT_TRUE(checker);
  const Hierarchy ht = build_hierarchy(checker_room(checker, true));
  const Hierarchy hs = build_hierarchy(checker_room(checker, false));
  const auto vt = make_visibility_backend(BackendKind::Embree, ht);
  const auto vs = make_visibility_backend(BackendKind::Embree, hs);
  SolverOptions o;
  const SolverState st = solve_shots(ht, *vt, o, 400);
  const SolverState ss = solve_shots(hs, *vs, o, 400);

  auto on_floor = [](const Hierarchy& h) {
    return [&h](size_t p) {
      return h.objects[size_t(h.triangles.object[p])].name.rfind("floor", 0) == 0;
    };
  };
  auto rest = [](const Hierarchy& h) {
    return [&h](size_t p) {
      return h.objects[size_t(h.triangles.object[p])].name.rfind("floor", 0) != 0;
    };
  };
  auto cell = [](const Vec3& c) {
    const int i = std::clamp(int(c.x * kSquares), 0, kSquares - 1);
    const int j = std::clamp(int(c.z * kSquares), 0, kSquares - 1);
    return size_t(i * kSquares + j);
  };
  auto one = [](const Vec3&) { return size_t(0); };
  const auto floor_t = integrate(st, on_floor(ht), cell, kSquares * kSquares);
  const auto floor_s = integrate(ss, on_floor(hs), cell, kSquares * kSquares);
  const DVec3 rest_t = integrate(st, rest(ht), one, 1)[0];
  const DVec3 rest_s = integrate(ss, rest(hs), one, 1)[0];

  // The walls and ceiling take what the floor reflects: the same light, per channel.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rest_t[k] / rest_s[k], 1.0, 0.005) << "channel " << k;
  // The floor reflects the same light in all, and each square receives the same light.
  const auto arriving_t = integrate(st, on_floor(ht), cell, kSquares * kSquares, true);
  const auto arriving_s = integrate(ss, on_floor(hs), cell, kSquares * kSquares, true);
  DVec3 total_t(0.0), total_s(0.0), diff(0.0), mean(0.0);
  for (size_t c = 0; c < floor_t.size(); ++c) {
    total_t += floor_t[c], total_s += floor_s[c];
    diff += glm::abs(arriving_t[c] - arriving_s[c]);
    mean += arriving_s[c];
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(total_t[k] / total_s[k], 1.0, 0.005) << "channel " << k;
    EXPECT_LT(diff[k] / mean[k], 0.005) << "channel " << k;
  }
  // The pattern shows: each square reflects its own colour. A vertex on a square's edge reads
  // both colours half and half, and the elements beside it blend them, so light squares lose
  // a little of what dark ones gain (7% of the contrast here); not a quarter of it.
  for (size_t c = 0; c < floor_t.size(); ++c) {
    for (int k = 0; k < 3; ++k) {
      const double contrast = std::abs(floor_s[0][k] - floor_s[1][k]);
      EXPECT_LT(std::abs(floor_t[c][k] - floor_s[c][k]), 0.25 * contrast)
          << "square " << c << " channel " << k;
    }
  }
}

TEST(TextureFactors, ACheckerEmitterLightsAsTheEmitterCutIntoColouredSquares) {
  const auto checker = checker_texture();
  ASSERT_TRUE(checker);
  const Hierarchy ht = build_hierarchy(checker_lit_room(checker, true));
  const Hierarchy hs = build_hierarchy(checker_lit_room(checker, false));
  const auto vt = make_visibility_backend(BackendKind::Embree, ht);
  const auto vs = make_visibility_backend(BackendKind::Embree, hs);
  SolverOptions o;
  const SolverState st = solve_shots(ht, *vt, o, 400);
  const SolverState ss = solve_shots(hs, *vs, o, 400);

  auto named = [](const Hierarchy& h, const char* name) {
    return [&h, name](size_t p) { return h.objects[size_t(h.triangles.object[p])].name == name; };
  };
  auto on_floor = [](const Hierarchy& h) {
    return [&h](size_t p) {
      return h.objects[size_t(h.triangles.object[p])].name.rfind("floor", 0) == 0;
    };
  };
  auto cell = [](const Vec3& c) {
    const int i = std::clamp(int(c.x * kSquares), 0, kSquares - 1);
    const int j = std::clamp(int(c.z * kSquares), 0, kSquares - 1);
    return size_t(i * kSquares + j);
  };
  // The floor emits the same power, square by square.
  const auto floor_t = integrate(st, on_floor(ht), cell, kSquares * kSquares);
  const auto floor_s = integrate(ss, on_floor(hs), cell, kSquares * kSquares);
  DVec3 total_t(0.0), total_s(0.0);
  for (size_t c = 0; c < floor_t.size(); ++c) {
    total_t += floor_t[c], total_s += floor_s[c];
    for (int k = 0; k < 3; ++k) {
      const double contrast = std::abs(floor_s[0][k] - floor_s[1][k]);
      EXPECT_LT(std::abs(floor_t[c][k] - floor_s[c][k]), 0.25 * contrast)
          << "square " << c << " channel " << k;
    }
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(total_t[k] / total_s[k], 1.0, 0.005) << "channel " << k;
  // The ceiling above receives the same light, cell by cell.
  const auto ceiling_t = integrate(st, named(ht, "ceiling"), cell, kSquares * kSquares, true);
  const auto ceiling_s = integrate(ss, named(hs, "ceiling"), cell, kSquares * kSquares, true);
  for (size_t c = 0; c < ceiling_t.size(); ++c) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(ceiling_t[c][k] / ceiling_s[c][k], 1.0, 0.01) << "cell " << c << " channel " << k;
    }
  }
}

}  // namespace
}  // namespace rad
