// Pictures by final gather: the direct light recomputed at each point has no fixed steps in a
// penumbra and matches the exact form factor there; the picture agrees with the solution it
// reads, shows textures at the pixel, and is the same for every backend and thread count.
#include "export/gathered_image.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "../solver/scene_builder.h"
#include "../solver/umbra_scene.h"
#include "export/image_render.h"
#include "export/output_mesh.h"
#include "export/polygon_locator.h"
#include "solver/direct_light.h"
#include "solver/shoot.h"

namespace rad {
namespace {

using testing::add_closed_box;
using testing::add_quad;
using testing::solve_shots;

using testing::exact_direct;
using testing::kBlockerHalf;
using testing::kLampEmission;
using testing::kLampHalf;
using testing::kLampHeight;
using testing::rectangle_factor;
using testing::umbra_scene;

TEST(GatheredImage, APenumbraAveragedOverTheEndSetsIsTheExactOneWithoutSteps) {
  const Hierarchy h = build_hierarchy(umbra_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = make_solver_state(h, SolverOptions{});
  constexpr uint32_t kSets = 16;
  const DirectLight direct = make_direct_light(s, kSets);
  ASSERT_EQ(direct.sources.size(), 1u);
  const PolygonLocator locator(h.triangles, h.bounds);
  std::vector<std::pair<uint32_t, int>> stack;
  DirectLightScratch scratch;
  // As a pixel gathers it: without the solver's penumbra rounds (the sets stand for them).
  GatherSettings g = gather_settings(s);
  g.penumbra_rays = 0;
  const double open = exact_direct(3.0, 0.0) > 0.0
                          ? kLampEmission * rectangle_factor(-kLampHalf, kLampHalf, -kLampHalf,
                                                             kLampHalf, kLampHeight)
                          : 0.0;
  // Across the penumbra (x from 0.85 to 1.15 at z = 0.05, h = 2): the mean over the sets
  // against the exact value, and set 0 alone (the ends every shot uses: 16 fixed points).
  double error_mean = 0.0, error_fixed = 0.0;
  int points = 0;
  std::vector<float> fixed_levels;
  for (int i = 0; i <= 60; ++i) {
    const float x = 0.82f + 0.36f * float(i) / 60.0f, z = 0.05f;
    const Vec3 at(x, 0.0f, z);
    const int32_t p = locator.locate(at, Vec3(0, 1, 0), stack);
    ASSERT_GE(p, 0);
    double mean = 0.0;
    for (uint32_t k = 0; k < kSets; ++k) {
      mean += direct_gain(s, direct, size_t(p), at, Vec3(0, 1, 0), k, *vis, g, scratch).x;
    }
    mean /= kSets;
    const float fixed = direct_gain(s, direct, size_t(p), at, Vec3(0, 1, 0), 0, *vis, g, scratch).x;
    const double exact = exact_direct(x, z);
    error_mean += std::abs(mean - exact);
    error_fixed += std::abs(double(fixed) - exact);
    fixed_levels.push_back(fixed);
    ++points;
  }
  error_mean /= points * open;
  error_fixed /= points * open;
  RecordProperty("error_mean", std::to_string(error_mean));
  RecordProperty("error_fixed", std::to_string(error_fixed));
  // Relative to the unshadowed light: the sets' mean within 1.5%, several times closer than
  // the fixed ends' steps.
  EXPECT_LT(error_mean, 0.015) << "fixed ends: " << error_fixed;
  EXPECT_LT(error_mean, 0.5 * error_fixed);
}

// A closed box lit by a ceiling lamp, with a block standing on its floor.
SceneDescription lit_box() {
  SceneDescription d;
  add_closed_box(d, Vec3(0.0f), Vec3(1.0f), Vec3(0.6f), Vec3(0.0f), 2);
  add_quad(d, "lamp", {0.4f, 0.4f, 0.999f}, {0.4f, 0.6f, 0.999f}, {0.6f, 0.6f, 0.999f},
           {0.6f, 0.4f, 0.999f}, Vec3(0.0f), Vec3(10.0f));  // facing down
  // A block on the floor (z = 0), its top at z = 0.3.
  const float a = 0.3f, b = 0.5f, t = 0.3f;
  add_quad(d, "block top", {a, a, t}, {b, a, t}, {b, b, t}, {a, b, t}, Vec3(0.7f), Vec3(0.0f));
  add_quad(d, "block x", {b, a, 0}, {b, b, 0}, {b, b, t}, {b, a, t}, Vec3(0.7f), Vec3(0.0f));
  add_quad(d, "block -x", {a, a, 0}, {a, a, t}, {a, b, t}, {a, b, 0}, Vec3(0.7f), Vec3(0.0f));
  add_quad(d, "block y", {a, b, 0}, {a, b, t}, {b, b, t}, {b, b, 0}, Vec3(0.7f), Vec3(0.0f));
  add_quad(d, "block -y", {a, a, 0}, {b, a, 0}, {b, a, t}, {a, a, t}, Vec3(0.7f), Vec3(0.0f));
  return d;
}

// Looking down from under the lamp onto the floor and the block.
Camera box_camera() { return Camera{{0.5f, 0.45f, 0.95f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}, 80.0f}; }

TEST(GatheredImage, EveryBackendAndThreadCountGivesTheSameBytes) {
  const Hierarchy h = build_hierarchy(lit_box());
  GatheredImageOptions o;
  o.width = o.height = 40;
  const auto embree = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = solve_shots(h, *embree, SolverOptions{}, 30);
  std::vector<Image> images;
  for (const BackendKind kind : {BackendKind::Embree, BackendKind::Grid, BackendKind::Brute}) {
    const auto vis = make_visibility_backend(kind, h);
    for (const int threads : {1, 2}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                      size_t(threads));
      images.push_back(render_gathered_image(s, *vis, box_camera(), o));
    }
  }
  for (size_t i = 1; i < images.size(); ++i) {
    ASSERT_EQ(images[i].pixels.size(), images[0].pixels.size());
    EXPECT_EQ(std::memcmp(images[i].pixels.data(), images[0].pixels.data(),
                          images[0].pixels.size() * sizeof(Vec3)),
              0)
        << "image " << i;
  }
}

TEST(GatheredImage, AgreesWithTheSolutionItReadsAwayFromShadowEdges) {
  const Hierarchy h = build_hierarchy(lit_box());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions so;
  const SolverState s = solve_shots(h, *vis, so, 400);
  GatheredImageOptions o;
  o.width = o.height = 64;
  const Image gathered = render_gathered_image(s, *vis, box_camera(), o);
  const OutputMesh mesh = make_output_mesh(s, false);
  RenderOptions ro;
  ro.width = ro.height = 64;
  const Image raster =
      render_image(mesh.position(), mesh.display, mesh.indices(), box_camera(), ro);
  // The whole picture: the same light, to the mesh's interpolation error at its edges.
  DVec3 sum_g(0.0), sum_r(0.0);
  for (size_t i = 0; i < gathered.pixels.size(); ++i) {
    sum_g += DVec3(gathered.pixels[i]), sum_r += DVec3(raster.pixels[i]);
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum_g[c] / sum_r[c], 1.0, 0.02) << "channel " << c;
  // The block's top, seen whole in the middle, lit directly and smoothly: within 1%.
  DVec3 top_g(0.0), top_r(0.0);
  for (int y = 28; y < 36; ++y) {
    for (int x = 28; x < 36; ++x)
      top_g += DVec3(gathered.at(x, y)), top_r += DVec3(raster.at(x, y));
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(top_g[c] / top_r[c], 1.0, 0.01) << "channel " << c;
}

TEST(GatheredImage, WhereNothingIsSeenThePixelsShowTheBackgroundOrAreTransparent) {
  const Hierarchy h = build_hierarchy(umbra_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = solve_shots(h, *vis, SolverOptions{}, 5);
  GatheredImageOptions o;
  o.width = o.height = 32;
  // From above, the 4 x 4 floor fills the middle of the view and the void its corners.
  const Camera camera{{0.0f, 6.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 60.0f};
  o.background = Vec3(0.25f, 0.5f, 0.75f);
  const Image coloured = render_gathered_image(s, *vis, camera, o);
  EXPECT_TRUE(coloured.alpha.empty());
  EXPECT_EQ(coloured.at(0, 0), o.background);
  o.transparent = true;
  const Image transparent = render_gathered_image(s, *vis, camera, o);
  ASSERT_EQ(transparent.alpha.size(), transparent.pixels.size());
  EXPECT_EQ(transparent.alpha[0], 0.0f);
  EXPECT_EQ(transparent.at(0, 0), Vec3(0.0f));
  const size_t middle = size_t(16) * 32 + 20;  // the floor beside the blocker
  EXPECT_EQ(transparent.alpha[middle], 1.0f);
  EXPECT_EQ(transparent.pixels[middle], coloured.pixels[middle]);
  EXPECT_GT(transparent.pixels[middle].x, 0.0f);
  // The floor's edge: some samples see it, some the void.
  size_t partial = 0;
  for (float a : transparent.alpha) partial += a > 0.0f && a < 1.0f;
  EXPECT_GT(partial, 0u);
}

// The vertices' bounced light is H less their direct light gathered again with the solver's own
// rays, penumbra rounds included: with or without them the picture is the same, the rounds
// changing only what the vertices hold, not what a pixel shows of the direct light.
TEST(GatheredImage, PenumbraRaysLeaveThePictureAsItIs) {
  const Hierarchy h = build_hierarchy(umbra_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  GatheredImageOptions o;
  o.width = o.height = 48;
  const Camera camera{{0.0f, 6.0f, 0.01f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 40.0f};
  std::vector<Image> images;
  for (const int rounds : {0, 8}) {
    SolverOptions options;
    options.penumbra_rays = rounds;
    SolverState s = make_solver_state(h, options);
    solve(s, *vis);
    images.push_back(render_gathered_image(s, *vis, camera, o));
  }
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < images[0].pixels.size(); ++i) {
    diff += double(max_component(glm::abs(images[0].pixels[i] - images[1].pixels[i])));
    sum += double(max_component(images[0].pixels[i]));
  }
  ASSERT_GT(sum, 0.0);
  EXPECT_LT(diff / sum, 1e-3) << "the pictures with 0 and 8 penumbra rounds differ";
}

std::shared_ptr<TextureImage> two_colour_image() {
  // 2 x 1 texels: red on the left half, blue on the right.
  const unsigned char p[8] = {200, 40, 40, 255, 40, 40, 200, 255};
  std::string bytes;
  stbi_write_png_to_func(
      [](void* out, void* data, int size) {
        static_cast<std::string*>(out)->append(static_cast<const char*>(data), size_t(size));
      },
      &bytes, 2, 1, 4, p, 8);
  return decode_texture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "2x1");
}

TEST(GatheredImage, ATextureShowsAtThePixelNotAtTheElement) {
  SceneDescription d = lit_box();
  // The floor (z = 0) textured: half red, half blue along x, on one element.
  const auto image = two_colour_image();
  ASSERT_TRUE(image);
  for (ObjectDescription& o : d.objects) {
    if (o.name != "bottom") continue;
    o.material.reflectance = image->mean;
    o.base_texture.image = image;
    o.base_texture.sampler.nearest = true;
    o.base_texture.sampler.wrap_s = o.base_texture.sampler.wrap_t = TextureWrap::ClampToEdge;
    o.triangle_uvs.clear();
    for (const auto& t : o.triangles) {
      o.triangle_uvs.push_back({Vec2(t[0].x, t[0].y), Vec2(t[1].x, t[1].y), Vec2(t[2].x, t[2].y)});
    }
  }
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = solve_shots(h, *vis, SolverOptions{}, 60);
  GatheredImageOptions o;
  o.width = o.height = 64;
  // Straight down onto the floor's middle strip, away from the block.
  const Camera camera{{0.5f, 0.8f, 0.9f}, {0.5f, 0.8f, 0.0f}, {0, 1, 0}, 30.0f};
  const Image picture = render_gathered_image(s, *vis, camera, o);
  // Just either side of the colour edge at x = 0.5 (the image's middle column; +x is on its
  // right, looking down with +y up), the colours are the texels': red on the left, blue on the
  // right, though one element spans both.
  const Vec3 left = picture.at(28, 32), right = picture.at(35, 32);
  const Vec3 red = image->levels[0].texels[0], blue = image->levels[0].texels[1];
  EXPECT_NEAR(left.x / left.z, red.x / red.z, 0.05 * red.x / red.z);
  EXPECT_NEAR(right.z / right.x, blue.z / blue.x, 0.05 * blue.z / blue.x);
}

}  // namespace
}  // namespace rad
