// Textures as the solver reads them: decoded to linear colour once, filtered over a footprint,
// wrapped as the sampler says; and the texture coordinates the glTF and OBJ readers hand on.
#include "scene/texture.h"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "hierarchy/hierarchy.h"
#include "scene/gltf_reader.h"
#include "scene/model_scene.h"
#include "scene/obj_reader.h"
#include "scene_texts.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// PNG bytes of a w x h RGBA image.
std::string png(int w, int h, const std::vector<unsigned char>& rgba) {
  std::string out;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
      },
      &out, w, h, 4, rgba.data(), w * 4);
  return out;
}

std::shared_ptr<TextureImage> decode(const std::string& bytes) {
  return decode_texture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "t");
}

// A 4 x 2 image: row 0 black, white, black, white; row 1 all sRGB 188 (linear ~0.5), the last
// texel half transparent.
std::string four_by_two() {
  std::vector<unsigned char> p;
  for (int x = 0; x < 4; ++x) {
    const unsigned char c = x % 2 ? 255 : 0;
    p.insert(p.end(), {c, c, c, 255});
  }
  for (int x = 0; x < 4; ++x)
    p.insert(p.end(), {188, 188, 188, (unsigned char)(x == 3 ? 128 : 255)});
  return png(4, 2, p);
}

TEST(Texture, DecodesToLinearColourWithAlphaAndMipLevels) {
  const auto t = decode(four_by_two());
  ASSERT_TRUE(t);
  ASSERT_EQ(t->levels.size(), 3u) << "4x2, 2x1, 1x1";
  EXPECT_EQ(t->levels[1].width, 2);
  EXPECT_EQ(t->levels[1].height, 1);
  const Vec4 grey = t->levels[0].texels[4];
  EXPECT_NEAR(grey.x, 0.5029f, 1e-3f) << "sRGB 188 decoded to linear";
  EXPECT_NEAR(t->levels[0].texels[7].w, 128.0f / 255.0f, 1e-6f) << "alpha stays linear";
  EXPECT_NEAR(t->mean.x, (2.0f * 1.0f + 4.0f * grey.x) / 8.0f, 1e-5f);
  EXPECT_NEAR(t->levels[2].texels[0].x, t->mean.x, 1e-5f) << "the last level is the mean";
}

TEST(Texture, SamplesTexelsWhenSmallAndTheMeanWhenTheFootprintCoversTheImage) {
  TextureMap m{decode(four_by_two()), {}};
  ASSERT_TRUE(m);
  // Texel centres of row 0, x = 1 (white) and x = 2 (black).
  EXPECT_NEAR(sample_texture(m, Vec2(1.5f / 4, 0.25f), 0.0f).x, 1.0f, 1e-6f);
  EXPECT_NEAR(sample_texture(m, Vec2(2.5f / 4, 0.25f), 0.0f).x, 0.0f, 1e-6f);
  // Between them, linear; nearest keeps the texel.
  EXPECT_NEAR(sample_texture(m, Vec2(2.0f / 4, 0.25f), 0.0f).x, 0.5f, 1e-6f);
  TextureMap nearest = m;
  nearest.sampler.nearest = true;
  EXPECT_NEAR(sample_texture(nearest, Vec2(1.9f / 4, 0.25f), 0.0f).x, 1.0f, 1e-6f);
  // A footprint as wide as the image reads its mean anywhere.
  for (const float u : {0.1f, 0.5f, 0.9f}) {
    EXPECT_NEAR(sample_texture(m, Vec2(u, 0.3f), 8.0f).x, m.image->mean.x, 1e-5f);
  }
  // Two texels wide at the row of alternating black and white: their mean, between levels 0 and 1.
  const float two = sample_texture(m, Vec2(1.0f / 4, 0.25f), 2.0f).x;
  EXPECT_GT(two, 0.3f);
  EXPECT_LT(two, 0.9f);
}

TEST(Texture, CoordinatesWrapAsTheSamplerSays) {
  TextureMap m{decode(four_by_two()), {}};
  const Vec2 white(1.5f / 4, 0.25f);
  const float inside = sample_texture(m, white, 0.0f).x;
  EXPECT_EQ(sample_texture(m, white + Vec2(3.0f, -2.0f), 0.0f).x, inside) << "repeat";
  m.sampler.wrap_s = TextureWrap::ClampToEdge;
  EXPECT_NEAR(sample_texture(m, Vec2(7.0f, 0.25f), 0.0f).x, 1.0f, 1e-6f) << "last texel, white";
  EXPECT_NEAR(sample_texture(m, Vec2(-7.0f, 0.25f), 0.0f).x, 0.0f, 1e-6f) << "first, black";
  m.sampler.wrap_s = TextureWrap::MirroredRepeat;
  // Mirrored: u = 1 + 0.375 reads u = 1 - 0.375 = texel 2 (black); u = 2.375 reads texel 1.
  EXPECT_NEAR(sample_texture(m, Vec2(1.375f, 0.25f), 0.0f).x, 0.0f, 1e-6f);
  EXPECT_NEAR(sample_texture(m, Vec2(2.375f, 0.25f), 0.0f).x, 1.0f, 1e-6f);
  // Non-finite and huge coordinates read a texel, never out of the image.
  for (const float bad : {NAN, INFINITY, -1e30f, 1e30f}) {
    for (const TextureWrap w :
         {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat}) {
      m.sampler.wrap_s = m.sampler.wrap_t = w;
      const Vec4 s = sample_texture(m, Vec2(bad, bad), bad);
      EXPECT_TRUE(std::isfinite(s.x) && s.x >= 0.0f && s.x <= 1.0f);
    }
  }
}

TEST(Texture, WhatIsNotAnImageIsNoTexture) {
  EXPECT_FALSE(decode("not a png"));
  const std::string ok = four_by_two();
  EXPECT_FALSE(decode(ok.substr(0, ok.size() / 2))) << "truncated";
  EXPECT_FALSE(decode(""));
  EXPECT_FALSE(read_texture_file("/nonexistent/rad/texture.png"));
}

// A PNG chunk whose length says more than the file holds is no texture. (stb_image refuses it
// too, but only after sizing its buffer by that length; that rad checks first is what the fuzz
// run's allocation limit holds, from tests/scene/fuzz_regressions/gltf/
// png_chunk_longer_than_its_file.gltf, which tools/fuzz seeds.)
TEST(Texture, APngChunkLongerThanItsFileIsNoTexture) {
  std::string bytes = four_by_two();
  const size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  ASSERT_TRUE(decode(bytes));
  for (const uint32_t length : {0x54000000u, uint32_t(bytes.size())}) {
    for (int k = 0; k < 4; ++k) bytes[idat - 4 + size_t(k)] = char(length >> (24 - 8 * k));
    EXPECT_FALSE(decode(bytes)) << length;
  }
}

// A unit quad with texture coordinates, its material's base texture (sampler: clamp in s,
// nearest) read through KHR_texture_transform.
// `image` is the PNG's bytes, embedded; with `uri` the image is that external file instead.
std::string textured_quad_gltf(const std::string& image, bool double_sided = false,
                               const std::string& alpha_mode = "OPAQUE",
                               const std::string& uri = "") {
  std::string buf;
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  buf.append(reinterpret_cast<const char*>(p), sizeof p);
  const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  buf.append(reinterpret_cast<const char*>(uv), sizeof uv);
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  buf.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                "material": 0}]}],
    "materials": [{"name": "Wood", "doubleSided": )" +
         std::string(double_sided ? "true" : "false") + R"(, "alphaMode": ")" + alpha_mode +
         R"(", "alphaCutoff": 0.625,
       "pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 1, 1],
       "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
          {"offset": [0, 1], "rotation": 1.5707963267948966, "scale": [0.5, 0.5]}}}}}],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728}],
    "images": [{"uri": ")" +
         (uri.empty() ? "data:image/png;base64," + testing::base64(image) : uri) + R"("}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,)" +
         testing::base64(buf) + R"("}]})";
}

TEST(TextureCoordinates, GltfReadsThemThroughTheTextureTransformWithItsSampler) {
  const Model m = parse_gltf(textured_quad_gltf(four_by_two()), "quad.gltf", "");
  ASSERT_EQ(m.materials.size(), 1u);
  const ModelMaterial& wood = m.materials[0];
  ASSERT_TRUE(wood.base_texture);
  EXPECT_NEAR(wood.reflectance.x, 0.5f * wood.base_texture.image->mean.x, 1e-6f)
      << "the factor times the texture's mean";
  EXPECT_EQ(wood.base_texture.sampler.wrap_s, TextureWrap::ClampToEdge);
  EXPECT_EQ(wood.base_texture.sampler.wrap_t, TextureWrap::MirroredRepeat);
  EXPECT_TRUE(wood.base_texture.sampler.nearest);
  ASSERT_EQ(m.groups.size(), 1u);
  const ModelGroup& g = m.groups[0];
  ASSERT_EQ(g.triangle_uvs.size(), g.triangles.size());
  // Offset (0, 1), a quarter turn, half scale: the extension's own example maps the quad to
  // the image's lower left quadrant, rotated: (1, 0) goes to (0, 0.5), (1, 1) to (0.5, 0.5).
  EXPECT_NEAR(g.triangle_uvs[0][1].x, 0.0f, 1e-6f);
  EXPECT_NEAR(g.triangle_uvs[0][1].y, 0.5f, 1e-6f);
  EXPECT_NEAR(g.triangle_uvs[0][2].x, 0.5f, 1e-6f);
  EXPECT_NEAR(g.triangle_uvs[0][2].y, 0.5f, 1e-6f);
  EXPECT_NEAR(g.triangle_uvs[0][0].x, 0.0f, 1e-6f);
  EXPECT_NEAR(g.triangle_uvs[0][0].y, 1.0f, 1e-6f);
}

TEST(TextureCoordinates, AnUndecodableGltfImageLeavesTheFactorAlone) {
  const Model m = parse_gltf(textured_quad_gltf("not an image"), "quad.gltf", "");
  EXPECT_FALSE(m.materials[0].base_texture);
  EXPECT_EQ(m.materials[0].reflectance.x, 0.5f);
  EXPECT_EQ(m.textures.unread, 1u);
  EXPECT_TRUE(m.groups[0].triangle_uvs.empty()) << "coordinates of no texture are not kept";
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(TextureCoordinates, AMissingOrUndecodableExternalGltfImageIsWarnedByItsFileName) {
  const fs::path dir = fs::temp_directory_path() / ("rad_gltf_image_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "garbled.png", std::ios::binary) << "not an image at all";
  ::testing::internal::CaptureStderr();
  const Model missing =
      parse_gltf(textured_quad_gltf("", false, "OPAQUE", "gone.png"), "quad.gltf", dir.string());
  std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(missing.materials[0].base_texture);
  EXPECT_NE(warned.find("quad.gltf: warning: File not found : gone.png"), std::string::npos)
      << warned;
  EXPECT_NE(warned.find("quad.gltf: warning: the image gone.png is not read; its material uses "
                        "its factor"),
            std::string::npos)
      << "every line of tinygltf's warnings: " << warned;
  EXPECT_EQ(count(warned, "warning"), 2u) << warned;

  ::testing::internal::CaptureStderr();
  const Model garbled =
      parse_gltf(textured_quad_gltf("", false, "OPAQUE", "garbled.png"), "quad.gltf", dir.string());
  warned = ::testing::internal::GetCapturedStderr();
  fs::remove_all(dir);
  EXPECT_FALSE(garbled.materials[0].base_texture);
  EXPECT_EQ(garbled.textures.unread, 1u);
  EXPECT_NE(warned.find("quad.gltf: warning: the image garbled.png cannot be decoded"),
            std::string::npos)
      << warned;
  EXPECT_EQ(count(warned, "warning"), 1u) << warned;

  // An embedded one is named by its index and the file.
  ::testing::internal::CaptureStderr();
  parse_gltf(textured_quad_gltf("not an image"), "quad.gltf", "");
  warned = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warned.find("warning: image 0 of quad.gltf cannot be decoded"), std::string::npos)
      << warned;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(TextureCoordinates, GltfSaysOnceEachWhatItDoesNotRender) {
  // The textured mesh placed twice without its coordinates, with vertex colours; a skin, an
  // animation and two extensions rad does not read; BLEND.
  std::string gltf = textured_quad_gltf(four_by_two(), false, "BLEND");
  gltf = replaced(gltf, R"("POSITION": 0, "TEXCOORD_0": 1})", R"("POSITION": 0, "COLOR_0": 0})");
  gltf = replaced(gltf, R"("nodes": [{"mesh": 0}])", R"("nodes": [{"mesh": 0}, {"mesh": 0}])");
  gltf = replaced(gltf, R"("scenes": [{"nodes": [0]}])", R"("scenes": [{"nodes": [0, 1]}])");
  gltf = replaced(gltf, R"({"asset": {"version": "2.0"},)",
                  R"({"asset": {"version": "2.0"}, "skins": [{"joints": [1]}],
                      "animations": [{"channels": [], "samplers": []}],
                      "extensionsUsed": ["KHR_materials_clearcoat", "KHR_texture_transform",
                                         "KHR_materials_transmission"],)");
  ::testing::internal::CaptureStderr();
  const Model m = parse_gltf(gltf, "leaf.gltf", "");
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangle_count(), 4u);
  for (const char* said :
       {"leaf.gltf: warning: 4 triangles of textured material 'Wood' (the first) have no texture "
        "coordinates (TEXCOORD_0): they reflect the texture's mean colour and are not cut out",
        "leaf.gltf: warning: the vertices' colours (COLOR_0) are ignored",
        "leaf.gltf: warning: 1 skins ignored", "leaf.gltf: warning: 1 animations ignored",
        "leaf.gltf: warning: the extensions KHR_materials_clearcoat, KHR_materials_transmission "
        "are used but rad ignores them",
        "leaf.gltf: warning: material 'Wood' has alphaMode BLEND, which rad cannot blend: it is "
        "read as MASK with alphaCutoff 0.5"}) {
    EXPECT_NE(warned.find(said), std::string::npos) << said << "\n" << warned;
  }
  EXPECT_EQ(count(warned, "warning"), 6u) << "one each: " << warned;
  // A file that has none of these says nothing.
  ::testing::internal::CaptureStderr();
  parse_gltf(textured_quad_gltf(four_by_two(), false, "MASK"), "leaf.gltf", "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(Texture, AnImageSharedByTwoMaterialsIsDecodedOnce) {
  // glTF: two textures (two samplers' worth) of one image.
  std::string gltf = textured_quad_gltf(four_by_two());
  gltf = replaced(gltf, R"("materials": [{"name": "Wood",)",
                  R"("materials": [{"name": "Oak", "pbrMetallicRoughness":
                     {"baseColorTexture": {"index": 1}}}, {"name": "Wood",)");
  gltf = replaced(gltf, R"("textures": [{"source": 0, "sampler": 0}])",
                  R"("textures": [{"source": 0, "sampler": 0}, {"source": 0}])");
  const Model g = parse_gltf(gltf, "two.gltf", "");
  ASSERT_EQ(g.materials.size(), 2u);
  ASSERT_TRUE(g.materials[0].base_texture);
  EXPECT_EQ(g.materials[0].base_texture.image, g.materials[1].base_texture.image);
  EXPECT_NE(g.materials[0].base_texture.sampler.wrap_s, g.materials[1].base_texture.sampler.wrap_s)
      << "each texture its own sampler over the one image";

  // OBJ: two materials naming one file, once through another spelling of its path.
  const fs::path dir = fs::temp_directory_path() / ("rad_shared_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "wood.png", std::ios::binary) << four_by_two();
  std::ofstream(dir / "two.mtl") << "newmtl Oak\nKd 1 1 1\nmap_Kd wood.png\n"
                                    "newmtl Pine\nKd 1 1 1\nmap_Kd ./wood.png\n"
                                    "newmtl Ash\nKd 1 1 1\nmap_Kd -clamp on wood.png\n";
  std::ofstream(dir / "two.obj") << "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n"
                                    "usemtl Oak\nf 1/1 2/1 3/1\nusemtl Pine\nf 1/1 2/1 3/1\n"
                                    "usemtl Ash\nf 1/1 2/1 3/1\n";
  const Model o = read_obj_file((dir / "two.obj").string(), SourceLoc{});
  fs::remove_all(dir);
  ASSERT_EQ(o.materials.size(), 3u);
  ASSERT_TRUE(o.materials[0].base_texture);
  EXPECT_EQ(o.materials[0].base_texture.image, o.materials[1].base_texture.image);
  EXPECT_EQ(o.materials[0].base_texture.image, o.materials[2].base_texture.image);
  EXPECT_EQ(o.textures.read, 3u);
}

TEST(TextureCoordinates, ObjTurnsVtUpsideDownToTheImagesRows) {
  const fs::path dir = fs::temp_directory_path() / ("rad_texture_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "checker.png", std::ios::binary) << four_by_two();
  std::ofstream(dir / "quad.mtl") << "newmtl Checker\nKd 1 1 1\nmap_Kd checker.png\n"
                                     "newmtl Plain\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "quad.obj") << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                     "usemtl Plain\nf 1 2 3\nusemtl Checker\nf 1/1 3/3 4/4\n"
                                     "f 2 3 4\n";
  const Model m = read_obj_file((dir / "quad.obj").string(), SourceLoc{});
  fs::remove_all(dir);
  ASSERT_EQ(m.groups.size(), 1u);
  const ModelGroup& g = m.groups[0];
  ASSERT_EQ(g.triangle_uvs.size(), 3u) << "one per triangle once any has them";
  EXPECT_TRUE(std::isnan(g.triangle_uvs[0][0].x)) << "an untextured face has none";
  EXPECT_TRUE(std::isnan(g.triangle_uvs[2][0].x)) << "a textured face without vt: its mean";
  EXPECT_EQ(g.triangle_uvs[1][0], Vec2(0.0f, 1.0f)) << "vt (0, 0) is the image's last row";
  EXPECT_EQ(g.triangle_uvs[1][1], Vec2(1.0f, 0.0f));
  EXPECT_TRUE(m.materials[g.material[1]].base_texture);
  EXPECT_FALSE(m.materials[g.material[0]].base_texture);
}

TEST(Cutouts, GltfMaskAndBlendCutOutTheBaseTexturesAlpha) {
  EXPECT_FALSE(parse_gltf(textured_quad_gltf(four_by_two()), "q.gltf", "").materials[0].cutout);
  const Model mask = parse_gltf(textured_quad_gltf(four_by_two(), false, "MASK"), "q.gltf", "");
  ASSERT_TRUE(mask.materials[0].cutout);
  EXPECT_EQ(mask.materials[0].cutout.cutoff, 0.625f);
  EXPECT_EQ(mask.materials[0].cutout.texture.image, mask.materials[0].base_texture.image)
      << "the base colour texture's alpha, decoded once";
  const Model blend = parse_gltf(textured_quad_gltf(four_by_two(), false, "BLEND"), "q.gltf", "");
  ASSERT_TRUE(blend.materials[0].cutout);
  EXPECT_EQ(blend.materials[0].cutout.cutoff, 0.5f) << "blending taken as a cut at one half";
  // The texel with alpha 128/255 is a hole at 0.625, not at 0.5.
  const Vec2 texel(3.5f / 4, 0.75f);
  EXPECT_FALSE(opaque_at(mask.materials[0].cutout, texel));
  EXPECT_TRUE(opaque_at(blend.materials[0].cutout, texel));
  EXPECT_TRUE(opaque_at(mask.materials[0].cutout, Vec2(0.5f / 4, 0.75f)));
}

TEST(Cutouts, ObjMapDCutsOutByItsAlphaOrItsGreyLevel) {
  const fs::path dir = fs::temp_directory_path() / ("rad_cutout_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::vector<unsigned char> grey = {255, 255, 255, 255, 0, 0, 0, 255};  // white, black
  std::ofstream(dir / "mask.png", std::ios::binary) << png(2, 1, grey);
  std::ofstream(dir / "leaf.mtl") << "newmtl Leaf\nKd 0.2 0.6 0.2\nmap_d mask.png\n";
  std::ofstream(dir / "leaf.obj") << "mtllib leaf.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nusemtl Leaf\nf 1/1 2/2 3/3\n";
  const Model m = read_obj_file((dir / "leaf.obj").string(), SourceLoc{});
  fs::remove_all(dir);
  const AlphaMask& cut = m.materials[0].cutout;
  ASSERT_TRUE(cut);
  EXPECT_TRUE(cut.from_red) << "no alpha in the image: its grey level";
  EXPECT_TRUE(opaque_at(cut, Vec2(0.1f, 0.5f)));
  EXPECT_FALSE(opaque_at(cut, Vec2(0.9f, 0.5f)));
  EXPECT_EQ(m.groups[0].triangle_uvs.size(), 1u) << "its coordinates are kept";
}

TEST(TwoSidedModels, AGltfDoubleSidedMaterialFacesBothWaysWithItsTexture) {
  for (const bool two : {false, true}) {
    ModelOptions o;
    o.require_emission = false;
    const Hierarchy h = build_hierarchy(
        model_to_scene(parse_gltf(textured_quad_gltf(four_by_two(), two), "quad.gltf", ""), o));
    ASSERT_EQ(h.triangles.size(), two ? 4u : 2u);
    if (!two) continue;
    EXPECT_EQ(h.triangles.normal[2], -h.triangles.normal[0]);
    // The back's corners b and c swap, and their texture coordinates with them.
    EXPECT_EQ(h.triangles.corners[2][1], h.triangles.corners[0][2]);
    EXPECT_EQ(h.triangles.uv[2][1], h.triangles.uv[0][2]);
    EXPECT_EQ(h.triangles.uv[2][0], h.triangles.uv[0][0]);
  }
}

TEST(TwoSidedModels, TwoSidedNamesObjMaterialsOrGroupsByPattern) {
  const std::string obj =
      "mtllib garden.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no hedge\nusemtl Leaf\nf 1 2 "
      "3\nusemtl Wall\n"
      "f 1 3 4\no house\nusemtl Wall\nf 1 2 3\nusemtl Leaf\nf 1 3 4\n";
  const std::string mtl = "newmtl Leaf\nKd 0.2 0.6 0.2\nnewmtl Wall\nKd 0.7 0.7 0.7\n";
  auto triangles = [&](const std::vector<std::string>& patterns) {
    ModelOptions o;
    o.require_emission = false;
    o.two_sided = patterns;
    return build_hierarchy(model_to_scene(parse_obj_text(obj, mtl, "garden.obj"), o))
        .triangles.size();
  };
  EXPECT_EQ(triangles({}), 4u);
  EXPECT_EQ(triangles({"Le*"}), 6u) << "Leaf in both groups";
  EXPECT_EQ(triangles({"hedge"}), 6u) << "the hedge, both its materials";
  EXPECT_EQ(triangles({"hedge", "Leaf"}), 7u) << "each face once, whichever rules match it";
  try {
    triangles({"Roof*"});
    ADD_FAILURE() << "a pattern matching nothing";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--two-sided 'Roof*' matches no material (Leaf, Wall)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rad
