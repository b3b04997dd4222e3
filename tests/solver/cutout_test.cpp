// A cut-out surface solves as the same surface cut as polygons: shadow rays pass its holes, and
// it receives, reflects and shoots only on its opaque part.
#include <gtest/gtest.h>

#include "scene_builder.h"
#include "solver/texture_factors.h"
#include "visibility/backend.h"

namespace rad {
namespace {

using testing::add_quad;

// A mask opaque on its left half (u < 0.5), clear on its right.
AlphaMask half_mask() {
  auto image = std::make_shared<TextureImage>();
  image->name = "half";
  image->has_alpha = true;
  TextureImage::Level l;
  l.width = l.height = 64;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) l.texels.push_back(Vec4(1.0f, 1.0f, 1.0f, x < 32 ? 1.0f : 0.0f));
  }
  image->levels.push_back(l);
  image->mean = Vec3(1.0f);
  AlphaMask m;
  m.texture.image = image;
  m.texture.sampler.wrap_s = m.texture.sampler.wrap_t = TextureWrap::ClampToEdge;
  return m;
}

// A 1 x 1 x 1 room lit by a ceiling panel, a leaf half-way up facing it: the square x, z in
// [0.2, 0.8] cut out to its half x < 0.5, or that half as polygons.
Hierarchy room(bool cut) {
  SceneDescription d;
  const Vec3 wall(0.6f), none(0.0f);
  add_quad(d, "floor", {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, wall, none);
  add_quad(d, "ceiling", {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, wall, none);
  add_quad(d, "lamp", {0.4f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.4f}, {0.6f, 0.999f, 0.6f},
           {0.4f, 0.999f, 0.6f}, none, Vec3(20.0f));
  add_quad(d, "x0", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, wall, none);
  add_quad(d, "x1", {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, wall, none);
  add_quad(d, "z0", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, wall, none);
  add_quad(d, "z1", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, wall, none);
  const float right = cut ? 0.8f : 0.5f;
  add_quad(d, "leaf", {0.2f, 0.5f, 0.2f}, {0.2f, 0.5f, 0.8f}, {right, 0.5f, 0.8f},
           {right, 0.5f, 0.2f}, Vec3(0.5f, 0.7f, 0.3f), none);
  if (cut) {
    ObjectDescription& leaf = d.objects.back();
    leaf.cutout = half_mask();
    auto uv = [](const Vec3& p) { return Vec2((p.x - 0.2f) / 0.6f, (p.z - 0.2f) / 0.6f); };
    for (const auto& t : leaf.triangles)
      leaf.triangle_uvs.push_back({uv(t[0]), uv(t[1]), uv(t[2])});
  }
  return build_hierarchy(d);
}

// Radiosity (or irradiance, `arriving`) integrated over the Pure `name`, in a 4 x 4 grid of
// bins over x and z.
std::vector<DVec3> integral(const Hierarchy& h, const SolverState& s, const std::string& name,
                            bool arriving) {
  std::vector<DVec3> bins(16, DVec3(0.0));
  for (size_t p = 0; p < h.triangles.size(); ++p) {
    if (h.objects[size_t(h.triangles.object[p])].name != name) continue;
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      auto value = [&](uint32_t v) {
        return arriving ? s.solution.vertex_states[p][v].irradiance : s.solution.radiosity(p, v);
      };
      const Vec3 c = (m.positions[el.v[0]] + m.positions[el.v[1]] + m.positions[el.v[2]]) / 3.0f;
      const size_t bin =
          size_t(std::clamp(int(c.x * 4), 0, 3) * 4 + std::clamp(int(c.z * 4), 0, 3));
      bins[bin] +=
          DVec3(value(el.v[0]) + value(el.v[1]) + value(el.v[2])) * (double(el.area) / 3.0);
    });
  }
  return bins;
}

DVec3 sum(const std::vector<DVec3>& v) {
  DVec3 s(0.0);
  for (const DVec3& x : v) s += x;
  return s;
}

TEST(Cutouts, ACutOutLeafSolvesAsTheLeafCutAsPolygons) {
  const Hierarchy cut = room(true), polygons = room(false);
  const auto vc = make_visibility_backend(BackendKind::Embree, cut);
  const auto vp = make_visibility_backend(BackendKind::Embree, polygons);
  const SolverState a = testing::solve_shots(cut, *vc, SolverOptions{}, 300);
  const SolverState b = testing::solve_shots(polygons, *vp, SolverOptions{}, 300);
  // The floor: the leaf's shadow is the half's, bin by bin, in the light arriving.
  const auto floor_a = integral(cut, a, "floor", true),
             floor_b = integral(polygons, b, "floor", true);
  const DVec3 floor_total = sum(floor_b);
  for (size_t i = 0; i < 16; ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(floor_a[i][k], floor_b[i][k], 0.005 * floor_total[k] / 16) << "bin " << i;
    }
  }
  // The leaf reflects from its opaque half only, and the room takes that light alike.
  const DVec3 leaf_a = sum(integral(cut, a, "leaf", false));
  const DVec3 leaf_b = sum(integral(polygons, b, "leaf", false));
  const DVec3 ceiling_a = sum(integral(cut, a, "ceiling", false));
  const DVec3 ceiling_b = sum(integral(polygons, b, "ceiling", false));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(leaf_a[k] / leaf_b[k], 1.0, 0.005) << "channel " << k;
    EXPECT_NEAR(ceiling_a[k] / ceiling_b[k], 1.0, 0.005) << "channel " << k;
  }
}

}  // namespace
}  // namespace rad
