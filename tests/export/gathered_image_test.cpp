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

TEST(GatheredImage, APenumbraGatheredAsAPixelDoesIsTheExactOneWithoutSteps) {
  const Hierarchy h = build_hierarchy(umbra_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = make_solver_state(h, SolverOptions{});
  constexpr uint32_t kSets = 16;
  const DirectLight direct = make_direct_light(s, kSets);
  ASSERT_EQ(direct.sources.size(), 1u);
  const PolygonLocator locator(h.triangles, h.bounds);
  std::vector<std::pair<uint32_t, int>> stack;
  DirectLightScratch scratch;
  const GatherSettings pixel = pixel_gather_settings(s);
  GatherSettings fixed_only = gather_settings(s);
  fixed_only.penumbra_rays = 0;
  const double open =
      kLampEmission * rectangle_factor(-kLampHalf, kLampHalf, -kLampHalf, kLampHalf, kLampHeight);
  // Across the penumbra (x from 0.82 to 1.18 at z = 0.05, h = 2): at each point the mean of 16
  // points a millimetre apart, one per set (a pixel's subsamples each draw theirs), against the
  // exact value; and set 0 alone without rounds (the ends every shot uses: 16 fixed points).
  double error_pixel = 0.0, error_fixed = 0.0;
  // The largest change from one point to the next of the difference to the exact value: a step.
  double step_pixel = 0.0, step_fixed = 0.0, last_pixel = 0.0, last_fixed = 0.0;
  int points = 0;
  for (int i = 0; i <= 60; ++i) {
    const float x = 0.82f + 0.36f * float(i) / 60.0f, z = 0.05f;
    double mean = 0.0;
    for (uint32_t k = 0; k < kSets; ++k) {
      const Vec3 at(x + 1e-3f * (float(k % 4) - 1.5f), 0.0f, z + 1e-3f * (float(k / 4) - 1.5f));
      const int32_t p = locator.locate(at, Vec3(0, 1, 0), stack);
      ASSERT_GE(p, 0);
      mean += direct_gain(s, direct, size_t(p), at, Vec3(0, 1, 0), k, *vis, pixel, scratch).x;
    }
    mean /= kSets;
    const Vec3 at(x, 0.0f, z);
    const int32_t p = locator.locate(at, Vec3(0, 1, 0), stack);
    ASSERT_GE(p, 0);
    const float fixed =
        direct_gain(s, direct, size_t(p), at, Vec3(0, 1, 0), 0, *vis, fixed_only, scratch).x;
    const double exact = exact_direct(x, z);
    error_pixel += std::abs(mean - exact);
    error_fixed += std::abs(double(fixed) - exact);
    if (points > 0) {
      step_pixel = std::max(step_pixel, std::abs((mean - exact) - last_pixel));
      step_fixed = std::max(step_fixed, std::abs((double(fixed) - exact) - last_fixed));
    }
    last_pixel = mean - exact, last_fixed = double(fixed) - exact;
    ++points;
  }
  error_pixel /= points * open;
  error_fixed /= points * open;
  RecordProperty("error_pixel", std::to_string(error_pixel));
  RecordProperty("error_fixed", std::to_string(error_fixed));
  RecordProperty("step_pixel", std::to_string(step_pixel / open));
  RecordProperty("step_fixed", std::to_string(step_fixed / open));
  // Relative to the unshadowed light: within 1.5%, a quarter of the step one stratum of 16 makes
  // (6%), and half the fixed ends' error or less; and no jump from one point to the next half as
  // large as the fixed ends' largest.
  EXPECT_LT(error_pixel, 0.015) << "fixed ends: " << error_fixed;
  EXPECT_LT(error_pixel, 0.5 * error_fixed);
  EXPECT_LT(step_pixel, 0.5 * step_fixed);
}

// band_scene: a lamp 1.2 m square, 15 cm over a grey floor, with a black board 5 cm under it
// over x >= 0: from floor point (x < 0, 0, z) the board hides all of the lamp but a band along
// its near edge, x from 0 to -x / 2, which weighs far more than its share of the nearest strata's
// area. Seen from above, the floor beside the lamp shows that band's light, as the solver's
// vertices do, not the band's share of the area (about half of it, with ends drawn by power).
TEST(GatheredImage, BesideALampCloseByThePixelsShowTheLightOfTheBandTheySee) {
  const Hierarchy h = build_hierarchy(testing::band_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  // The floor's light meets only black faces: nothing comes back, and the picture is the floor's
  // reflectance times the direct light.
  const SolverState s = solve_shots(h, *vis, SolverOptions{}, 2);
  GatheredImageOptions o;
  o.width = o.height = 16;
  // Looking straight down at x from -0.175 to -0.075 (image rows), z from -0.05 to 0.05.
  const Camera camera{{-0.125f, 1.0f, 0.0f}, {-0.125f, 0.0f, 0.0f}, {1, 0, 0}, 5.72f};
  const Image picture = render_gathered_image(s, *vis, camera, o);
  const CameraFrame f = camera_frame(camera, 1.0f);
  double shown = 0.0, exact = 0.0;
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      const float u = (float(x) + 0.5f) / float(o.width), v = (float(y) + 0.5f) / float(o.height);
      const Vec3 dir = glm::normalize(f.forward + f.right * ((2.0f * u - 1.0f) * f.tan_half_x) +
                                      f.up * ((1.0f - 2.0f * v) * f.tan_half_y));
      const Vec3 at = camera.eye + dir * (camera.eye.y / -dir.y);
      ASSERT_LT(at.x, 0.0f);
      exact += 0.5 * testing::exact_band_direct(at.x, at.z);  // the floor's reflectance
      shown += double(picture.at(x, y).x);
    }
  }
  RecordProperty("exact", std::to_string(exact));
  RecordProperty("shown", std::to_string(shown));
  // The bound of the solver's own test (penumbra_test.cpp, the same band): the ends are drawn
  // uniformly inside each fine point's cell, across which the light still varies.
  EXPECT_NEAR(shown, exact, 0.15 * exact);
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
