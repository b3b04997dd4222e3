#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "export/mesh_file.h"
#include "gltf_validator.h"
#include "mesh_parts.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::path(RAD_BINARY_DIR) / "test_out" / "mesh_formats";
  fs::create_directories(d);
  return d;
}

/// Two polygons: a quad (two faces) and a triangle, with radiosity above and below 1.
testing::MeshParts sample_mesh() {
  testing::MeshParts m;
  m.position = {Vec3(0, 0, 0),     Vec3(1.5f, 0, 0), Vec3(1.5f, 2, 0),         Vec3(0, 2, 0.25f),
                Vec3(-1, 0.5f, 3), Vec3(-2, 1, 3),   Vec3(-1.5f, 2.5f, 3.125f)};
  m.radiosity = {
      Vec3(0.1f, 0.2f, 0.3f),  Vec3(1.0f, 0.5f, 0.25f),  Vec3(2.0f, 3.0f, 4.0f), Vec3(0.0f),
      Vec3(12.0f, 8.0f, 3.0f), Vec3(0.01f, 0.02f, 0.7f), Vec3(0.5f, 0.5f, 0.5f)};
  for (const Vec3& b : m.radiosity) m.display.push_back(b + Vec3(0.05f, 0.03f, 0.01f));
  for (const Vec3& b : m.radiosity) m.irradiance.push_back(b * 2.0f + Vec3(0.0f, 0.5f, 1.0f));
  m.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6};
  m.face_polygon = {0, 0, 1};
  return m;
}

const ToneMap kTone{0.7f, ToneCurve::Reinhard};

std::string write(const std::string& name, const testing::MeshParts& m, bool ascii = false) {
  const std::string path = (temp_dir() / name).string();
  MeshFileOptions o;
  o.tone = kTone;
  o.ascii = ascii;
  write_mesh_file(path, m.view(), o);
  return path;
}

Vec3 srgb_unit(const Vec3& display) {
  uint8_t c[3];
  to_srgb8(display, kTone, c);
  return Vec3(c[0], c[1], c[2]) / 255.0f;
}

// ---- PLY: a small reader for the properties rad writes --------------------------------------

struct PlyData {
  std::vector<std::array<float, 3>> xyz, radiosity, irradiance;
  std::vector<std::array<int, 3>> rgb;
  std::vector<std::vector<uint32_t>> faces;
};

template <typename T>
T read_binary(std::istream& in) {
  T v;
  in.read(reinterpret_cast<char*>(&v), sizeof v);
  return v;
}

PlyData read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  size_t nv = 0, nf = 0;
  std::vector<std::string> vprops;  // "float x", "uchar red", ...
  std::string element;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream l(line);
    std::string word;
    l >> word;
    if (word == "format") {
      l >> format;
    } else if (word == "element") {
      l >> element;
      (element == "vertex" ? l >> nv : l >> nf);
    } else if (word == "property" && element == "vertex") {
      std::string type, name;
      l >> type >> name;
      vprops.push_back(type + " " + name);
    } else if (word == "property") {
      EXPECT_EQ(line, "property list uchar uint vertex_indices");
    }
  }
  const std::vector<std::string> expected = {"float x",
                                             "float y",
                                             "float z",
                                             "uchar red",
                                             "uchar green",
                                             "uchar blue",
                                             "float radiosity_r",
                                             "float radiosity_g",
                                             "float radiosity_b",
                                             "float irradiance_r",
                                             "float irradiance_g",
                                             "float irradiance_b"};
  EXPECT_EQ(vprops, expected);
  const bool ascii = format == "ascii";
  EXPECT_TRUE(ascii || format == "binary_little_endian");
  PlyData d;
  for (size_t v = 0; v < nv; ++v) {
    std::array<float, 3> p, b, h;
    std::array<int, 3> c;
    if (ascii) {
      in >> p[0] >> p[1] >> p[2] >> c[0] >> c[1] >> c[2] >> b[0] >> b[1] >> b[2] >> h[0] >> h[1] >>
          h[2];
    } else {
      for (float& x : p) x = read_binary<float>(in);
      for (int& x : c) x = read_binary<uint8_t>(in);
      for (float& x : b) x = read_binary<float>(in);
      for (float& x : h) x = read_binary<float>(in);
    }
    d.xyz.push_back(p), d.rgb.push_back(c), d.radiosity.push_back(b), d.irradiance.push_back(h);
  }
  for (size_t f = 0; f < nf; ++f) {
    int n = 0;
    if (ascii) {
      in >> n;
    } else {
      n = read_binary<uint8_t>(in);
    }
    std::vector<uint32_t> idx(static_cast<size_t>(n));
    for (uint32_t& i : idx) {
      if (ascii) {
        in >> i;
      } else {
        i = read_binary<uint32_t>(in);
      }
    }
    d.faces.push_back(idx);
  }
  EXPECT_TRUE(in) << path;
  if (!ascii) {
    EXPECT_EQ(in.peek(), std::char_traits<char>::eof()) << path;
  }
  return d;
}

void check_ply(const std::string& path, const testing::MeshParts& m, float tol) {
  const PlyData d = read_ply(path);
  ASSERT_EQ(d.xyz.size(), m.position.size());
  for (size_t v = 0; v < m.position.size(); ++v) {
    uint8_t c[3];
    to_srgb8(m.display[v], kTone, c);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d.xyz[v][size_t(k)], m.position[v][k], tol);
      EXPECT_EQ(d.rgb[v][size_t(k)], int(c[k]));
      EXPECT_NEAR(d.radiosity[v][size_t(k)], m.radiosity[v][k], tol);
      EXPECT_NEAR(d.irradiance[v][size_t(k)], m.irradiance[v][k], tol);
    }
  }
  ASSERT_EQ(d.faces.size(), m.face_count());
  for (size_t f = 0; f < m.face_count(); ++f) {
    EXPECT_EQ(d.faces[f], std::vector<uint32_t>(&m.indices[3 * f], &m.indices[3 * f] + 3));
  }
}

TEST(MeshFormats, BinaryPlyRoundTrips) {
  check_ply(write("m.ply", sample_mesh()), sample_mesh(), 0);
}

TEST(MeshFormats, AsciiPlyRoundTrips) {
  check_ply(write("m_ascii.ply", sample_mesh(), true), sample_mesh(), 1e-6f);
}

// ---- OFF and OBJ ----------------------------------------------------------------------------

TEST(MeshFormats, CoffRoundTripsWithDisplayColoursInUnitRange) {
  const testing::MeshParts m = sample_mesh();
  std::ifstream in(write("m.off", m));
  std::string magic;
  size_t nv = 0, nf = 0, ne = 1;
  in >> magic >> nv >> nf >> ne;
  EXPECT_EQ(magic, "COFF");
  ASSERT_EQ(nv, m.position.size());
  ASSERT_EQ(nf, m.face_count());
  EXPECT_EQ(ne, 0u);
  for (size_t v = 0; v < nv; ++v) {
    Vec3 p, c;
    float a = 0;
    in >> p.x >> p.y >> p.z >> c.r >> c.g >> c.b >> a;
    EXPECT_EQ(p, m.position[v]);
    const Vec3 want = srgb_unit(m.display[v]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], want[k], 1e-6f) << "vertex " << v;
    EXPECT_EQ(a, 1.0f);
  }
  for (size_t f = 0; f < nf; ++f) {
    uint32_t n = 0, i[3];
    in >> n >> i[0] >> i[1] >> i[2];
    EXPECT_EQ(n, 3u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(i[k], m.indices[3 * f + size_t(k)]);
  }
  EXPECT_TRUE(in);
  std::string rest;
  EXPECT_FALSE(in >> rest) << rest;
}

TEST(MeshFormats, ObjRoundTripsWithVertexColours) {
  const testing::MeshParts m = sample_mesh();
  std::ifstream in(write("m.obj", m));
  std::string line;
  size_t v = 0, f = 0;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string tag;
    l >> tag;
    if (tag == "v") {
      ASSERT_LT(v, m.position.size());
      Vec3 p, c;
      l >> p.x >> p.y >> p.z >> c.r >> c.g >> c.b;
      EXPECT_TRUE(l) << line;
      EXPECT_EQ(p, m.position[v]);
      const Vec3 want = srgb_unit(m.display[v]);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], want[k], 1e-6f) << line;
      ++v;
    } else if (tag == "f") {
      ASSERT_LT(f, m.face_count());
      uint32_t i[3];
      l >> i[0] >> i[1] >> i[2];
      for (int k = 0; k < 3; ++k) EXPECT_EQ(i[k], m.indices[3 * f + size_t(k)] + 1) << line;
      ++f;
    } else {
      EXPECT_TRUE(tag.empty() || tag[0] == '#') << line;
    }
  }
  EXPECT_EQ(v, m.position.size());
  EXPECT_EQ(f, m.face_count());
}

// ---- glTF -----------------------------------------------------------------------------------

std::vector<Vec3> read_vec3(const tinygltf::Model& g, int accessor) {
  const tinygltf::Accessor& a = g.accessors[size_t(accessor)];
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(a.type, TINYGLTF_TYPE_VEC3);
  const tinygltf::BufferView& view = g.bufferViews[size_t(a.bufferView)];
  const size_t stride = view.byteStride ? view.byteStride : 12;
  const unsigned char* base =
      g.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
  std::vector<Vec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i], base + i * stride, 12);
  return out;
}

void check_gltf(const std::string& path, bool binary) {
  const testing::MeshParts m = sample_mesh();
  tinygltf::TinyGLTF loader;
  tinygltf::Model g;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&g, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&g, &err, &warn, path);
  ASSERT_TRUE(ok) << err;
  EXPECT_EQ(g.asset.version, "2.0");
  ASSERT_EQ(g.meshes.size(), 1u);
  ASSERT_EQ(g.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& p = g.meshes[0].primitives[0];
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);

  EXPECT_EQ(read_vec3(g, p.attributes.at("POSITION")), m.position);
  EXPECT_EQ(read_vec3(g, p.attributes.at("_RADIOSITY")), m.radiosity);
  const std::vector<Vec3> colour = read_vec3(g, p.attributes.at("COLOR_0"));
  ASSERT_EQ(colour.size(), m.display.size());
  for (size_t v = 0; v < colour.size(); ++v) {
    EXPECT_EQ(colour[v], tone_map(m.display[v], kTone)) << "vertex " << v;  // linear, 0-1
  }
  const tinygltf::Accessor& pos = g.accessors[size_t(p.attributes.at("POSITION"))];
  EXPECT_EQ(pos.minValues, (std::vector<double>{-2, 0, 0}));
  EXPECT_EQ(pos.maxValues, (std::vector<double>{1.5, 2.5, 3.125}));

  const tinygltf::Accessor& idx = g.accessors[size_t(p.indices)];
  ASSERT_EQ(idx.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  ASSERT_EQ(idx.count, m.indices.size());
  const tinygltf::BufferView& view = g.bufferViews[size_t(idx.bufferView)];
  std::vector<uint32_t> indices(idx.count);
  std::memcpy(indices.data(), g.buffers[0].data.data() + view.byteOffset + idx.byteOffset,
              indices.size() * 4);
  EXPECT_EQ(indices, m.indices);

  ASSERT_EQ(g.materials.size(), 1u);
  EXPECT_EQ(p.material, 0);
  EXPECT_EQ(g.materials[0].extensions.count("KHR_materials_unlit"), 1u);
  EXPECT_EQ(g.extensionsUsed, std::vector<std::string>{"KHR_materials_unlit"});
  EXPECT_FALSE(g.materials[0].doubleSided);
  ASSERT_EQ(g.scenes.size(), 1u);
  EXPECT_EQ(g.scenes[0].nodes, std::vector<int>{0});
  EXPECT_EQ(g.nodes[0].mesh, 0);
}

TEST(MeshFormats, GltfRoundTrips) { check_gltf(write("m.gltf", sample_mesh()), false); }
TEST(MeshFormats, GlbRoundTrips) { check_gltf(write("m.glb", sample_mesh()), true); }

TEST(MeshFormats, GlbStartsWithTheBinaryHeader) {
  std::ifstream in(write("m.glb", sample_mesh()), std::ios::binary);
  char magic[4];
  uint32_t version = 0, length = 0;
  in.read(magic, 4);
  in.read(reinterpret_cast<char*>(&version), 4);
  in.read(reinterpret_cast<char*>(&length), 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(length, fs::file_size(temp_dir() / "m.glb"));
  EXPECT_EQ(length % 4, 0u);
}

/// Runs the Khronos glTF validator through node; skips when node or the npm package is missing.
TEST(MeshFormats, KhronosValidatorReportsNoErrors) {
  testing::MeshParts big = sample_mesh();
  const testing::ValidatorRun r = testing::run_gltf_validator(
      {write("v.gltf", big), write("v.glb", big)}, temp_dir() / "validator.log");
  if (!r.skipped.empty()) GTEST_SKIP() << r.skipped;
  EXPECT_EQ(r.status, 0) << r.report;
  EXPECT_NE(r.report.find("v.gltf: 0 errors"), std::string::npos) << r.report;
  EXPECT_NE(r.report.find("v.glb: 0 errors"), std::string::npos) << r.report;
}

// Light groups: each group's radiosity per vertex, as PLY properties named in the header's
// comments and as glTF attributes named in the mesh's extras.
TEST(MeshFormats, LightGroupsAreWrittenAsPlyPropertiesAndGltfAttributes) {
  const testing::MeshParts parts = sample_mesh();
  OutputMesh m = parts.view();
  m.group_names = {"panel", "desk lamp"};
  for (const float share : {0.25f, 0.75f}) {
    std::vector<Vec3> b;
    for (const Vec3& x : parts.radiosity) b.push_back(x * share);
    m.group_radiosity.push_back(b);
  }
  MeshFileOptions o;
  o.tone = kTone;
  o.ascii = true;
  const std::string ply = (temp_dir() / "groups.ply").string();
  write_mesh_file(ply, m, o);
  std::ifstream in(ply);
  std::string line, header;
  while (std::getline(in, line) && line != "end_header") header += line + "\n";
  EXPECT_NE(header.find("comment light group 0 \"panel\""), std::string::npos) << header;
  EXPECT_NE(header.find("comment light group 1 \"desk lamp\""), std::string::npos) << header;
  EXPECT_NE(header.find("property float irradiance_b\nproperty float group0_r\nproperty float "
                        "group0_g\nproperty float group0_b\nproperty float group1_r\n"),
            std::string::npos)
      << header;
  for (size_t v = 0; v < m.position().size(); ++v) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream l(line);
    std::vector<float> x;
    for (float f; l >> f;) x.push_back(f);
    ASSERT_EQ(x.size(), 18u) << line;
    for (int k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(x[12 + size_t(k)], m.group_radiosity[0][v][k]);
      EXPECT_FLOAT_EQ(x[15 + size_t(k)], m.group_radiosity[1][v][k]);
    }
  }

  const std::string gltf = (temp_dir() / "groups.gltf").string();
  write_mesh_file(gltf, m, o);
  tinygltf::TinyGLTF loader;
  tinygltf::Model g;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&g, &err, &warn, gltf)) << err;
  ASSERT_EQ(g.meshes.size(), 1u);
  const tinygltf::Primitive& p = g.meshes[0].primitives[0];
  EXPECT_EQ(read_vec3(g, p.attributes.at("_RADIOSITY_GROUP_0")), m.group_radiosity[0]);
  EXPECT_EQ(read_vec3(g, p.attributes.at("_RADIOSITY_GROUP_1")), m.group_radiosity[1]);
  const tinygltf::Value& names = g.meshes[0].extras.Get("light_groups");
  ASSERT_TRUE(names.IsArray());
  ASSERT_EQ(names.ArrayLen(), 2u);
  EXPECT_EQ(names.Get(0).Get<std::string>(), "panel");
  EXPECT_EQ(names.Get(1).Get<std::string>(), "desk lamp");
}

TEST(MeshFormats, ExtensionChoosesTheFormatAndUnknownOnesAreRejected) {
  for (const char* ok : {"a.ply", "a.PLY", "b.off", "c.obj", "d.gltf", "e.GLB", "f.gfo"}) {
    EXPECT_NO_THROW(check_mesh_extension(ok)) << ok;
  }
  for (const char* bad : {"a.stl", "a", "a.ply.bak"}) {
    EXPECT_THROW(check_mesh_extension(bad), Error) << bad;
  }
}

TEST(MeshFormats, AnEmptyMeshStillWritesValidFiles) {
  const testing::MeshParts empty;
  for (const char* name : {"e.ply", "e.off", "e.obj", "e.gltf", "e.glb"}) {
    EXPECT_NO_THROW(write(name, empty)) << name;
    EXPECT_TRUE(fs::exists(temp_dir() / name)) << name;
  }
  check_ply((temp_dir() / "e.ply").string(), empty, 0);
}

}  // namespace
}  // namespace rad
