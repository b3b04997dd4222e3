// Cut-outs: a shadow ray passes where a cut-out triangle's mask is below its cutoff, and every
// backend says so alike, through the same texel test.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "backend_params.h"
#include "visibility/backend.h"
#include "visibility/triangle_test.h"

namespace rad {
namespace {

constexpr int kTexels = 16, kBlock = 4;  // a 4 x 4 checker of opaque and clear blocks

bool opaque_block(float u, float v) {
  const int bx = int(u * kTexels) / kBlock, by = int(v * kTexels) / kBlock;
  return (bx + by) % 2 == 0;
}

AlphaMask checker_mask() {
  auto image = std::make_shared<TextureImage>();
  image->name = "checker alpha";
  image->has_alpha = true;
  TextureImage::Level l;
  l.width = l.height = kTexels;
  for (int y = 0; y < kTexels; ++y) {
    for (int x = 0; x < kTexels; ++x) {
      const bool opaque = ((x / kBlock) + (y / kBlock)) % 2 == 0;
      l.texels.push_back(Vec4(0.5f, 0.5f, 0.5f, opaque ? 1.0f : 0.0f));
    }
  }
  image->levels.push_back(l);
  AlphaMask m;
  m.texture.image = image;
  m.texture.sampler.nearest = true;
  m.texture.sampler.wrap_s = m.texture.sampler.wrap_t = TextureWrap::ClampToEdge;
  return m;
}

// The square [-1, 1]^2 at height z facing +z, cut into n x n cells of two triangles, with
// u = (x + 1) / 2, v = (y + 1) / 2; cut out by the checker when `cut`.
ObjectDescription square(const char* name, float z, int n, bool cut) {
  ObjectDescription o;
  o.name = name;
  o.material.reflectance = Vec3(0.5f);
  if (cut) o.cutout = checker_mask();
  auto uv = [](const Vec3& p) { return Vec2((p.x + 1.0f) / 2.0f, (p.y + 1.0f) / 2.0f); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const float x0 = -1 + 2.0f * i / n, x1 = -1 + 2.0f * (i + 1) / n;
      const float y0 = -1 + 2.0f * j / n, y1 = -1 + 2.0f * (j + 1) / n;
      const Vec3 a(x0, y0, z), b(x1, y0, z), c(x1, y1, z), d(x0, y1, z);
      o.triangles.push_back({a, b, c});
      o.triangles.push_back({a, c, d});
      o.triangle_uvs.push_back({uv(a), uv(b), uv(c)});
      o.triangle_uvs.push_back({uv(a), uv(c), uv(d)});
    }
  }
  return o;
}

Hierarchy scene(int n) {
  SceneDescription s;
  s.name = "cut-out";
  s.objects = {square("leaf", 0.0f, n, true), square("floor", -0.5f, 1, false)};
  s.roots = {0, 1};
  return build_hierarchy(s);
}

class Cutout : public testing::TestWithParam<BackendParam> {
 protected:
  std::unique_ptr<VisibilityBackend> make(const Hierarchy& h) {
    VisibilityOptions options;
    options.packets = GetParam().packets;
    return make_visibility_backend(GetParam().kind, h, options);
  }
};

TEST_P(Cutout, ShadowRaysPassTheHolesAndStopOnTheOpaqueTexels) {
  for (const int n : {1, 3, 24}) {  // 24: dense grid cells, traced eight triangles at a time
    const Hierarchy h = scene(n);
    const auto b = make(h);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> in_block(0.1f, 0.9f);
    std::uniform_int_distribution<int> block(0, kTexels / kBlock - 1);
    std::vector<Segment> s;
    std::vector<uint8_t> expected;
    for (int i = 0; i < 400; ++i) {
      // Away from the blocks' edges: which block is met is certain.
      const float u = (float(block(rng)) + in_block(rng)) * kBlock / kTexels;
      const float v = (float(block(rng)) + in_block(rng)) * kBlock / kTexels;
      const float x = 2.0f * u - 1.0f, y = 2.0f * v - 1.0f;
      s.push_back({Vec3(x, y, 1.0f), Vec3(0.0f, 0.0f, -1.2f)});  // ends above the floor
      expected.push_back(opaque_block(u, v));
    }
    std::vector<uint8_t> out(s.size());
    VisibilityStats stats;
    b->occluded(s, out, stats);
    EXPECT_EQ(out, expected) << "n = " << n;
    size_t clear = std::count(expected.begin(), expected.end(), 0);
    EXPECT_GT(clear, 100u);
    EXPECT_GT(s.size() - clear, 100u);
  }
}

TEST_P(Cutout, EveryBackendAgreesWithBruteForceOnObliqueRays) {
  const Hierarchy h = scene(24);
  const auto b = make(h);
  const auto brute = make_visibility_backend(BackendKind::Brute, h);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> p(-1.3f, 1.3f);
  std::vector<Segment> s;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 from(p(rng), p(rng), 0.8f), to(p(rng), p(rng), -0.4f);
    s.push_back({from, to - from});
  }
  std::vector<uint8_t> mine(s.size()), reference(s.size());
  VisibilityStats stats;
  b->occluded(s, mine, stats);
  brute->occluded(s, reference, stats);
  EXPECT_EQ(mine, reference);
  // And the nearest surface: through a hole, the floor below.
  for (size_t i = 0; i < 300; ++i) {
    const SegmentHit a = b->first_hit(s[i], stats), r = brute->first_hit(s[i], stats);
    ASSERT_EQ(a.hit, r.hit) << i;
    if (a.hit) {
      EXPECT_EQ(a.t, r.t) << i;
    }
  }
}

TEST_P(Cutout, FirstHitThroughAHoleIsTheSurfaceBeyond) {
  const Hierarchy h = scene(3);
  const auto b = make(h);
  VisibilityStats stats;
  // Block (0, 0) is opaque, block (1, 0) clear: u in [0.25, 0.5).
  const SegmentHit opaque = b->first_hit({Vec3(-0.9f, -0.9f, 1.0f), Vec3(0, 0, -2)}, stats);
  const SegmentHit clear = b->first_hit({Vec3(-0.3f, -0.9f, 1.0f), Vec3(0, 0, -2)}, stats);
  ASSERT_TRUE(opaque.hit && clear.hit);
  EXPECT_NEAR(opaque.t, 0.5f, 1e-5f) << "the leaf, at z = 0";
  EXPECT_NEAR(clear.t, 0.75f, 1e-5f) << "the floor, at z = -0.5";
}

INSTANTIATE_TEST_SUITE_P(AllBackends, Cutout, kAllBackends, backend_param_name);

}  // namespace
}  // namespace rad
