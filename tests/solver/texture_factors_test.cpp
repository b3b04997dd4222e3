// A textured surface reflects per vertex: its texture filtered over the element the vertex
// stands for. A checker-textured floor solves as the same floor cut into coloured squares.
#include "solver/texture_factors.h"

#include <gtest/gtest.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cmath>
#include <utility>

#include "hierarchy/auto_hierarchy.h"
#include "scene_builder.h"
#include "visibility/backend.h"

namespace rad {
namespace {

using testing::add_quad;
using testing::solve_shots;

constexpr int kSquares = 4, kTexels = 64;  // a 4 x 4 checker, 16 texels a square
const unsigned char kLight[3] = {230, 60, 40}, kDark[3] = {40, 160, 200};

std::shared_ptr<TextureImage> checker_image() {
  std::vector<unsigned char> p;
  for (int y = 0; y < kTexels; ++y) {
    for (int x = 0; x < kTexels; ++x) {
      const bool light = (x * kSquares / kTexels + y * kSquares / kTexels) % 2 == 0;
      const unsigned char* c = light ? kLight : kDark;
      p.insert(p.end(), {c[0], c[1], c[2], 255});
    }
  }
  std::string bytes;
  stbi_write_png_to_func(
      [](void* out, void* data, int size) {
        static_cast<std::string*>(out)->append(static_cast<const char*>(data), size_t(size));
      },
      &bytes, kTexels, kTexels, 4, p.data(), kTexels * 4);
  return decode_texture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(),
                        "checker");
}

// The floor square (i, j)'s corners, x from i, z from j, at y = 0, facing up (+y); texture
// coordinates u along x, v along z.
std::array<Vec3, 4> square(float i0, float j0, float i1, float j1) {
  return {Vec3(i0, 0, j0), Vec3(i0, 0, j1), Vec3(i1, 0, j1), Vec3(i1, 0, j0)};
}

// A 1 x 1 x 1 room lit by a ceiling panel; its floor checker-textured, or cut into squares.
SceneDescription room(const std::shared_ptr<TextureImage>& checker, bool textured) {
  SceneDescription d;
  const Vec3 wall(0.6f), none(0.0f);
  add_quad(d, "ceiling", {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, wall, none);
  add_quad(d, "lamp", {0.4f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.6f},
           {0.4f, 0.999f, 0.6f}, none, Vec3(20.0f));
  add_quad(d, "x0", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, wall, none);
  add_quad(d, "x1", {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, wall, none);
  add_quad(d, "z0", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, wall, none);
  add_quad(d, "z1", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, wall, none);
  if (textured) {
    ObjectDescription o;
    o.name = "floor";
    o.material = {checker->mean, none};  // Kd 1 times the texture's mean
    o.base_texture.image = checker;
    const std::array<Vec3, 4> q = square(0, 0, 1, 1);
    o.triangles = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
    auto uv = [](const Vec3& p) { return Vec2(p.x, p.z); };
    o.triangle_uvs = {{uv(q[0]), uv(q[1]), uv(q[2])}, {uv(q[0]), uv(q[2]), uv(q[3])}};
    d.roots.push_back(int32_t(d.objects.size()));
    d.objects.push_back(std::move(o));
  } else {
    const TextureImage::Level& l = checker->levels.front();
    for (int i = 0; i < kSquares; ++i) {
      for (int j = 0; j < kSquares; ++j) {
        // The square's colour as decoded: a texel in its middle.
        const int x = i * kTexels / kSquares + 2, y = j * kTexels / kSquares + 2;
        const Vec4 c = l.texels[size_t(y) * size_t(l.width) + size_t(x)];
        const float s = 1.0f / kSquares;
        const std::array<Vec3, 4> q = square(i * s, j * s, (i + 1) * s, (j + 1) * s);
        add_quad(d, "floor " + std::to_string(i) + " " + std::to_string(j), q[0], q[1], q[2], q[3],
                 Vec3(c), none);
      }
    }
  }
  return d;
}

// The same room lit by its floor alone: a checker-textured emitter, or squares each emitting
// their colour.
SceneDescription room_lit_by_the_floor(const std::shared_ptr<TextureImage>& checker,
                                       bool textured) {
  SceneDescription d = room(checker, textured);
  for (ObjectDescription& o : d.objects) {
    if (o.name == "lamp") o.material.emission = Vec3(0.0f);
    if (o.name.rfind("floor", 0) != 0) continue;
    o.material.emission = o.material.reflectance;
    o.material.reflectance = Vec3(0.0f);
    if (textured) o.emissive_texture = std::exchange(o.base_texture, {});
  }
  return d;
}

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
  const auto checker = checker_image();
  ASSERT_TRUE(checker);
  const SceneDescription d = room(checker, true);
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
  const auto checker = checker_image();
  const Hierarchy h = build_hierarchy(room(checker, true));
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
  const auto checker = checker_image();
  ASSERT_TRUE(checker);
  const Hierarchy ht = build_hierarchy(room(checker, true));
  const Hierarchy hs = build_hierarchy(room(checker, false));
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
  // a little of what dark ones gain (3% of the contrast here); not a quarter of it.
  for (size_t c = 0; c < floor_t.size(); ++c) {
    for (int k = 0; k < 3; ++k) {
      const double contrast = std::abs(floor_s[0][k] - floor_s[1][k]);
      EXPECT_LT(std::abs(floor_t[c][k] - floor_s[c][k]), 0.25 * contrast)
          << "square " << c << " channel " << k;
    }
  }
}

TEST(TextureFactors, ACheckerEmitterLightsAsTheEmitterCutIntoColouredSquares) {
  const auto checker = checker_image();
  ASSERT_TRUE(checker);
  const Hierarchy ht = build_hierarchy(room_lit_by_the_floor(checker, true));
  const Hierarchy hs = build_hierarchy(room_lit_by_the_floor(checker, false));
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
