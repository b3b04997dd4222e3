// A textured scene solved and written keeps its textures: the output mesh carries each
// vertex's texture coordinates, glTF embeds each image once and bakes the light into COLOR_0 so
// that baseColorTexture x COLOR_0 is the display colour, OBJ names its images in an MTL, and PLY
// carries s t.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "../solver/scene_builder.h"
#include "export/mesh_file.h"
#include "export/texture_png.h"
#include "gltf_validator.h"
#include "hierarchy/auto_hierarchy.h"
#include "visibility/backend.h"

namespace rad {
namespace {

namespace fs = std::filesystem;
using testing::add_quad;

fs::path temp_dir() {
  const fs::path d = fs::path(RAD_BINARY_DIR) / "test_out" / "texture_output";
  fs::create_directories(d);
  return d;
}

/// An image from 8-bit sRGB RGBA texels, decoded as a model's texture is: from a PNG of them
/// (made by encode_png from the texels' linear values, the PNG a user's file would be).
std::shared_ptr<TextureImage> image_of(int w, int h, const std::vector<unsigned char>& rgba,
                                       const std::string& name) {
  auto linear = [](unsigned char c) {
    const double s = c / 255.0;
    return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
  };
  TextureImage raw;
  raw.name = name;
  raw.levels.resize(1);
  raw.levels[0].width = w, raw.levels[0].height = h;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    raw.levels[0].texels.push_back(Vec4(linear(rgba[i]), linear(rgba[i + 1]), linear(rgba[i + 2]),
                                        float(rgba[i + 3]) / 255.0f));
    raw.has_alpha |= rgba[i + 3] != 255;
  }
  const std::string png = encode_png(raw);
  return decode_texture(reinterpret_cast<const unsigned char*>(png.data()), png.size(), name);
}

constexpr int kSquares = 4, kTexels = 32;

/// A 4 x 4 checker, opaque.
std::shared_ptr<TextureImage> checker() {
  std::vector<unsigned char> p;
  for (int y = 0; y < kTexels; ++y) {
    for (int x = 0; x < kTexels; ++x) {
      const bool light = (x * kSquares / kTexels + y * kSquares / kTexels) % 2 == 0;
      p.insert(p.end(), {light ? uint8_t(230) : uint8_t(40), light ? uint8_t(60) : uint8_t(160),
                         light ? uint8_t(40) : uint8_t(200), 255});
    }
  }
  return image_of(kTexels, kTexels, p, "checker");
}

/// A green disc on a transparent ground: a cut-out sign.
std::shared_ptr<TextureImage> disc() {
  std::vector<unsigned char> p;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const float dx = x - 7.5f, dy = y - 7.5f;
      const bool in = dx * dx + dy * dy < 36.0f;
      p.insert(p.end(), {uint8_t(40 + 8 * x), 200, uint8_t(30 + 8 * y), uint8_t(in ? 255 : 0)});
    }
  }
  return image_of(16, 16, p, "disc");
}

/// A textured object: quad a b c d (as add_quad) with texture coordinates ta tb tc td.
void add_textured_quad(SceneDescription& d, const std::string& name, std::array<Vec3, 4> q,
                       std::array<Vec2, 4> t, const TextureMap& texture, bool cut_out) {
  ObjectDescription o;
  o.name = name;
  o.material = {texture.image->mean, Vec3(0.0f)};  // factor 1 times the texture's mean
  o.base_texture = texture;
  if (cut_out) o.cutout = AlphaMask{texture, false, 1.0f, 0.5f};
  o.triangles = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
  o.triangle_uvs = {{t[0], t[1], t[2]}, {t[0], t[2], t[3]}};
  o.triangle_locs.resize(2);
  d.roots.push_back(int32_t(d.objects.size()));
  d.objects.push_back(std::move(o));
}

/// A 1 x 1 x 1 room lit by a ceiling panel: its floor two checker-textured halves (the same
/// image, repeated and clamped), a cut-out disc standing on it.
SceneDescription room(const std::shared_ptr<TextureImage>& squares,
                      const std::shared_ptr<TextureImage>& sign) {
  SceneDescription d = room_without_floor();
  // The floor faces up; u along x, v along z.
  auto floor = [](float x0, float x1) {
    return std::array<Vec3, 4>{Vec3(x0, 0, 0), Vec3(x0, 0, 1), Vec3(x1, 0, 1), Vec3(x1, 0, 0)};
  };
  auto uv = [](const std::array<Vec3, 4>& q) {
    return std::array<Vec2, 4>{Vec2(q[0].x, q[0].z), Vec2(q[1].x, q[1].z), Vec2(q[2].x, q[2].z),
                               Vec2(q[3].x, q[3].z)};
  };
  TextureMap repeat{squares, {}}, clamp{squares, {}};
  clamp.sampler.wrap_s = clamp.sampler.wrap_t = TextureWrap::ClampToEdge;
  add_textured_quad(d, "floor left", floor(0, 0.5f), uv(floor(0, 0.5f)), repeat, false);
  add_textured_quad(d, "floor right", floor(0.5f, 1), uv(floor(0.5f, 1)), clamp, false);
  // The sign faces +z, towards the lamp, v down the image as y goes up.
  const std::array<Vec3, 4> s = {Vec3(0.7f, 0.2f, 0.3f), Vec3(0.7f, 0.6f, 0.3f),
                                 Vec3(0.3f, 0.6f, 0.3f), Vec3(0.3f, 0.2f, 0.3f)};
  add_textured_quad(d, "sign", s, {Vec2(1, 1), Vec2(1, 0), Vec2(0, 0), Vec2(0, 1)},
                    TextureMap{sign, {}}, true);
  return d;
}

/// The sign's texture coordinates at a point of it.
Vec2 sign_uv(const Vec3& p) { return Vec2((p.x - 0.3f) / 0.4f, (0.6f - p.y) / 0.4f); }

struct Solved {
  std::shared_ptr<TextureImage> squares = checker(), sign = disc();
  Hierarchy h = build_hierarchy(room(squares, sign));
  std::unique_ptr<VisibilityBackend> vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = testing::solve_shots(h, *vis, SolverOptions{}, 12);
};

const Solved& solved() {
  static const Solved s;
  return s;
}

const ToneMap kTone{1.5f, ToneCurve::Clamp};

/// Bright enough that the light on the checker's dark squares exceeds white.
const ToneMap kBright{8.0f, ToneCurve::Clamp};

std::string write(const std::string& name, const OutputMesh& m, bool ascii = false,
                  const ToneMap& tone = kTone) {
  const std::string path = (temp_dir() / name).string();
  MeshFileOptions o;
  o.tone = tone;
  o.ascii = ascii;
  write_mesh_file(path, m, o);
  return path;
}

template <typename T>
std::vector<T> accessor_data(const tinygltf::Model& g, int index) {
  const tinygltf::Accessor& a = g.accessors[size_t(index)];
  const tinygltf::BufferView& v = g.bufferViews[size_t(a.bufferView)];
  std::vector<T> out(a.count);
  std::memcpy(out.data(), g.buffers[size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset,
              a.count * sizeof(T));
  return out;
}

bool texels_equal(const TextureImage& a, const TextureImage& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.levels[0].texels.data(), b.levels[0].texels.data(),
                     a.levels[0].texels.size() * sizeof(Vec4)) == 0;
}

TEST(TextureOutput, TheOutputMeshKeepsEveryVertexsTextureCoordinates) {
  const Solved& x = solved();
  const OutputMesh m = make_output_mesh(x.s, true);
  ASSERT_EQ(m.uv().size(), m.position().size());
  ASSERT_EQ(m.texel.size(), m.position().size());
  ASSERT_EQ(m.face_texture().size(), m.face_count());
  // Two floor halves (one image, two samplers) and the sign.
  ASSERT_EQ(m.textures().size(), 3u);
  EXPECT_EQ(m.textures()[0].map.image, m.textures()[1].map.image);
  EXPECT_FALSE(m.textures()[0].mask);
  EXPECT_TRUE(m.textures()[2].mask);
  size_t floor = 0, sign = 0, untextured = 0;
  for (size_t f = 0; f < m.face_count(); ++f) {
    const int32_t k = m.face_texture()[f];
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = m.indices()[3 * f + size_t(c)];
      const Vec3& p = m.position()[v];
      // Every vertex of a face (its own, centroids and seam vertices) maps through the face's
      // triangle: the floor's u, v are x, z.
      if (k == 0 || k == 1) {
        EXPECT_NEAR(m.uv()[v].x, p.x, 1e-6f) << "floor vertex " << v;
        EXPECT_NEAR(m.uv()[v].y, p.z, 1e-6f) << "floor vertex " << v;
        ++floor;
      } else if (k == 2) {
        EXPECT_NEAR(m.uv()[v].x, sign_uv(p).x, 2e-6f) << "sign vertex " << v;
        EXPECT_NEAR(m.uv()[v].y, sign_uv(p).y, 2e-6f) << "sign vertex " << v;
        ++sign;
      } else {
        EXPECT_EQ(m.uv()[v], Vec2(0.0f));
        EXPECT_EQ(m.texel[v], Vec3(1.0f));
        ++untextured;
      }
    }
  }
  EXPECT_GT(floor, 12u);
  EXPECT_GT(sign, 6u);
  EXPECT_GT(untextured, 12u);
}

TEST(TextureOutput, AnUntexturedSceneCarriesNoTextureData) {
  SceneDescription d;
  add_quad(d, "floor", {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, Vec3(0.5f), Vec3(0.0f));
  add_quad(d, "lamp", {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, Vec3(0.0f), Vec3(1.0f));
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const OutputMesh m = make_output_mesh(testing::solve_shots(h, *vis, SolverOptions{}, 2), true);
  EXPECT_TRUE(m.uv().empty());
  EXPECT_TRUE(m.textures().empty());
  EXPECT_TRUE(m.face_texture().empty());
  EXPECT_TRUE(m.texel.empty());
}

TEST(TextureOutput, PngKeepsTheBytesReadIn) {
  const auto a = checker(), b = disc();
  for (const auto& image : {a, b}) {
    const std::string png = encode_png(*image);
    const auto back =
        decode_texture(reinterpret_cast<const unsigned char*>(png.data()), png.size(), "back");
    ASSERT_TRUE(back);
    EXPECT_TRUE(texels_equal(*image, *back)) << image->name;
    EXPECT_EQ(back->has_alpha, image->has_alpha);
  }
}

tinygltf::Model read_gltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model g;
  std::string err, warn;
  const bool ok = path.ends_with(".glb") ? loader.LoadBinaryFromFile(&g, &err, &warn, path)
                                         : loader.LoadASCIIFromFile(&g, &err, &warn, path);
  EXPECT_TRUE(ok) << err;
  return g;
}

/// The factor every COLOR_0 of a textured file is scaled by to stay within 0-1.
float colour_scale(const tinygltf::Model& g) {
  const tinygltf::Value& extras = g.meshes.at(0).extras;
  EXPECT_TRUE(extras.Has("colour_scale"));
  return float(extras.Get("colour_scale").GetNumberAsDouble());
}

/// Reads a glTF or GLB rad wrote and checks it against `m`: each image once, as read; the
/// texture coordinates as the mesh has them; baseColorTexture x COLOR_0 the display colour
/// (times the file's colour scale), COLOR_0 within 0-1.
void check_gltf(const std::string& path, const OutputMesh& m, const ToneMap& tone) {
  const tinygltf::Model g = read_gltf(path);
  ASSERT_EQ(g.meshes.size(), 1u);
  const float scale = colour_scale(g);
  const Solved& x = solved();
  // The checker and the disc, each embedded once though the checker shows on two materials.
  ASSERT_EQ(g.images.size(), 2u);
  std::vector<std::shared_ptr<TextureImage>> images;
  for (const tinygltf::Image& i : g.images) {
    EXPECT_EQ(i.mimeType, "image/png");
    ASSERT_GE(i.bufferView, 0);
    const tinygltf::BufferView& v = g.bufferViews[size_t(i.bufferView)];
    images.push_back(decode_texture(g.buffers[0].data.data() + v.byteOffset, v.byteLength, "gltf"));
    ASSERT_TRUE(images.back());
  }
  EXPECT_TRUE(texels_equal(*images[0], *x.squares));
  EXPECT_TRUE(texels_equal(*images[1], *x.sign));
  ASSERT_EQ(g.textures.size(), 3u);  // checker repeated, checker clamped, disc
  ASSERT_EQ(g.samplers.size(), 2u);
  ASSERT_EQ(g.materials.size(), 4u);
  for (const tinygltf::Material& mat : g.materials) {
    EXPECT_TRUE(mat.extensions.count("KHR_materials_unlit")) << mat.name;
  }
  const std::vector<tinygltf::Primitive>& prims = g.meshes[0].primitives;
  ASSERT_EQ(prims.size(), 4u);
  EXPECT_FALSE(prims[0].attributes.count("TEXCOORD_0"));
  EXPECT_EQ(g.materials[size_t(prims[0].material)].pbrMetallicRoughness.baseColorTexture.index, -1);
  const std::vector<Vec3> colour = accessor_data<Vec3>(g, prims[0].attributes.at("COLOR_0"));
  ASSERT_EQ(colour.size(), m.position().size());
  for (const Vec3& c : colour) ASSERT_LE(max_component(c), 1.0f);

  size_t point_sampled = 0;  // corners of textured faces
  for (size_t k = 1; k < prims.size(); ++k) {
    const tinygltf::Primitive& p = prims[k];
    const tinygltf::Material& mat = g.materials[size_t(p.material)];
    const int t = mat.pbrMetallicRoughness.baseColorTexture.index;
    ASSERT_GE(t, 0);
    EXPECT_EQ(mat.alphaMode, k == 3 ? "MASK" : "OPAQUE");
    const std::vector<Vec2> uv = accessor_data<Vec2>(g, p.attributes.at("TEXCOORD_0"));
    EXPECT_EQ(uv, m.uv());
    const tinygltf::Sampler& gs = g.samplers[size_t(g.textures[size_t(t)].sampler)];
    TextureMap map{images[size_t(g.textures[size_t(t)].source)], {}};
    if (gs.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE)
      map.sampler.wrap_s = map.sampler.wrap_t = TextureWrap::ClampToEdge;
    for (uint32_t v : accessor_data<uint32_t>(g, p.indices)) {
      const Vec3 shown = tone_map(m.display[v], tone) * scale;
      // The brightest light clamps when the scale alone would dim the file by over two stops.
      if (max_component(colour[v]) == 1.0f) continue;
      // At the texture as the solver filtered it over the vertex's element: exactly.
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(m.texel[v][c] * colour[v][c], shown[c], 1e-5f) << "vertex " << v;
      // As a viewer samples the image at the vertex: where that is the filtered colour (the
      // element lies within one square of the checker), within the 8-bit rounding of the image.
      const Vec3 seen = Vec3(sample_texture(map, uv[v], 0.0f));
      if (max_component(glm::abs(seen - m.texel[v])) > 0.5f / 255.0f) continue;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(seen[c] * colour[v][c], shown[c], 1.0f / 255.0f) << "vertex " << v;
      ++point_sampled;
    }
  }
  EXPECT_GT(point_sampled, 1000u);
}

TEST(TextureOutput, GltfEmbedsEachImageOnceAndBakesTheLightIntoColour0) {
  const OutputMesh m = make_output_mesh(solved().s, true);
  check_gltf(write("room.glb", m), m, kTone);
  check_gltf(write("room.gltf", m), m, kTone);
  EXPECT_EQ(colour_scale(read_gltf(write("room.glb", m))), 1.0f);
}

TEST(TextureOutput, LightBrighterThanWhiteOnADarkTextureScalesTheFilesColoursIntoRange) {
  const OutputMesh m = make_output_mesh(solved().s, true);
  const std::string path = write("bright.glb", m, false, kBright);
  check_gltf(path, m, kBright);
  const float scale = colour_scale(read_gltf(path));
  EXPECT_LT(scale, 1.0f);
  EXPECT_GE(scale, 0.25f);
}

TEST(TextureOutput, Colour0IsTheIrradianceTimesTheExposureBelowWhite) {
  // Without the ambient term, on a surface that does not emit, under the clamp curve below
  // white: COLOR_0 = scale x factor x H, and the floor's factor is 1.
  const OutputMesh m = make_output_mesh(solved().s, false);
  const tinygltf::Model g = read_gltf(write("plain.glb", m));
  ASSERT_EQ(colour_scale(g), 1.0f);
  const std::vector<Vec3> colour =
      accessor_data<Vec3>(g, g.meshes[0].primitives[0].attributes.at("COLOR_0"));
  size_t n = 0;
  for (size_t f = 0; f < m.face_count(); ++f) {
    if (m.face_texture()[f] != 0 && m.face_texture()[f] != 1) continue;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = m.indices()[3 * f + size_t(c)];
      if (max_component(m.display[v]) * kTone.scale >= 1.0f) continue;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(colour[v][k], kTone.scale * m.irradiance[v][k],
                    1e-4f * (1.0f + kTone.scale * m.irradiance[v][k]))
            << "vertex " << v;
      }
      ++n;
    }
  }
  EXPECT_GT(n, 40u);
}

TEST(TextureOutput, TheTexturedGltfValidates) {
  const OutputMesh m = make_output_mesh(solved().s, true);
  const testing::ValidatorRun r = testing::run_gltf_validator(
      {write("valid.gltf", m), write("valid.glb", m), write("bright.glb", m, false, kBright)},
      temp_dir() / "validator.log");
  if (!r.skipped.empty()) GTEST_SKIP() << r.skipped;
  EXPECT_EQ(r.status, 0) << r.report;
  EXPECT_NE(r.report.find("valid.gltf: 0 errors, 0 warnings"), std::string::npos) << r.report;
  EXPECT_NE(r.report.find("valid.glb: 0 errors, 0 warnings"), std::string::npos) << r.report;
  EXPECT_NE(r.report.find("bright.glb: 0 errors, 0 warnings"), std::string::npos) << r.report;
}

TEST(TextureOutput, ObjNamesItsImagesInAnMtlAndReadsBackWithItsCoordinates) {
  const Solved& x = solved();
  const OutputMesh m = make_output_mesh(x.s, true);
  const fs::path dir = temp_dir() / "obj";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "room.obj").string();
  MeshFileOptions o;
  o.tone = kTone;
  // Without its name, an OBJ is written alone.
  write_mesh_file(path, m, o);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  std::ifstream alone(path);
  const std::string lone((std::istreambuf_iterator<char>(alone)), std::istreambuf_iterator<char>());
  EXPECT_EQ(lone.find("\nvt "), std::string::npos);
  EXPECT_EQ(lone.find("mtllib"), std::string::npos);

  o.obj_name = path;
  write_mesh_file(path, m, o);
  // The OBJ, its MTL and one PNG per image.
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"room.mtl", "room.obj", "room_texture0.png",
                                             "room_texture2.png"}));
  std::ifstream mtl(dir / "room.mtl");
  const std::string text((std::istreambuf_iterator<char>(mtl)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("newmtl texture1\nKd 1 1 1\nillum 0\nmap_Kd -clamp on room_texture0.png"),
            std::string::npos)
      << text;

  // Read back as a model: the textured faces keep their coordinates and images.
  ModelOptions mo;
  mo.require_emission = false;
  const Hierarchy back = load_hierarchy(path, mo, HierarchyMode::AsRead);
  std::map<std::array<float, 9>, std::array<Vec2, 3>> wrote;
  for (size_t f = 0; f < m.face_count(); ++f) {
    if (m.face_texture()[f] < 0) continue;
    std::array<float, 9> key;
    std::array<Vec2, 3> uv;
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = m.indices()[3 * f + size_t(c)];
      for (int k = 0; k < 3; ++k) key[size_t(3 * c + k)] = m.position()[v][k];
      uv[size_t(c)] = m.uv()[v];
    }
    wrote[key] = uv;
  }
  ASSERT_EQ(back.triangles.uv.size(), back.triangles.size());
  size_t textured = 0;
  for (size_t t = 0; t < back.triangles.size(); ++t) {
    const SceneObject& obj = back.objects[size_t(back.triangles.object[t])];
    if (!obj.base_texture) continue;
    ++textured;
    EXPECT_TRUE(texels_equal(*obj.base_texture.image,
                             obj.name.find("texture2") != std::string::npos ? *x.sign : *x.squares))
        << obj.name;
    std::array<float, 9> key;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) key[size_t(3 * c + k)] = back.triangles.corners[t][size_t(c)][k];
    }
    const auto it = wrote.find(key);
    ASSERT_NE(it, wrote.end()) << "triangle " << t;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(back.triangles.uv[t][size_t(c)].x, it->second[size_t(c)].x, 1e-6f);
      EXPECT_NEAR(back.triangles.uv[t][size_t(c)].y, it->second[size_t(c)].y, 1e-6f);
    }
  }
  EXPECT_EQ(textured, wrote.size());
}

TEST(TextureOutput, PlyCarriesSAndT) {
  const OutputMesh m = make_output_mesh(solved().s, true);
  std::ifstream in(write("room.ply", m, true));
  std::string line;
  std::vector<std::string> properties;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("property float ", 0) == 0) properties.push_back(line.substr(15));
  }
  ASSERT_GE(properties.size(), 2u);
  EXPECT_EQ(properties[properties.size() - 2], "s");
  EXPECT_EQ(properties.back(), "t");
  for (size_t v = 0; v < m.position().size(); ++v) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream row(line);
    std::vector<float> x;
    for (float f; row >> f;) x.push_back(f);
    ASSERT_EQ(x.size(), 14u);
    EXPECT_EQ(x[12], m.uv()[v].x) << "vertex " << v;
    EXPECT_EQ(x[13], 1.0f - m.uv()[v].y) << "vertex " << v;
  }
}

}  // namespace
}  // namespace rad
