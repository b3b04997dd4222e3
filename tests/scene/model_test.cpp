// Model files as scenes: OBJ + MTL (tinyobjloader) and PLY, their materials, --emit, and the
// errors a user meets.
#include <gtest/gtest.h>
#include <unistd.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "hierarchy/hierarchy.h"
#include "scene/model.h"
#include "scene/model_scene.h"
#include "scene/obj_reader.h"
#include "scene/parser.h"
#include "scene/ply_reader.h"
#include "scene/scene_file.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

class ModelFiles : public ::testing::Test {
 protected:
  ModelFiles() : dir(fs::temp_directory_path() / ("rad_models_" + std::to_string(getpid()))) {
    fs::create_directories(dir);
  }
  ~ModelFiles() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  }
  fs::path dir;
};

// A floor, a lamp above it, and a crate; the crate textured half black, half white.
const char* kRoomObj = R"(# a room
mtllib room.mtl
v 0 0 0
v 4 0 0
v 4 0 4
v 0 0 4
v 1.5 3 1.5
v 2.5 3 1.5
v 2.5 3 2.5
v 1.5 3 2.5
o floor
usemtl Floor
f 1 4 3 2
o lamp
usemtl LampShade
f 5 6 7 8
o crate
usemtl Crate
f 1 2 5
usemtl Floor
f 2 3 6
)";
const char* kRoomMtl = R"(newmtl Floor
Kd 0.5 0.5 0.5
newmtl LampShade
Kd 0.9 0.8 0.4
newmtl Crate
Kd 1.2 0.5 0.5
map_Kd crate.png
)";

TEST_F(ModelFiles, ObjGroupsBecomeCompositesAndMaterialsPures) {
  const unsigned char pixels[6] = {0, 0, 0, 255, 255, 255};  // black and white
  ASSERT_TRUE(stbi_write_png((dir / "crate.png").c_str(), 2, 1, 3, pixels, 6));
  write("room.mtl", kRoomMtl);
  const Model m = read_obj_file(write("room.obj", kRoomObj), SourceLoc{});
  ASSERT_EQ(m.groups.size(), 3u);
  EXPECT_EQ(m.groups[0].name, "floor");
  EXPECT_EQ(m.groups[0].triangles.size(), 2u) << "the quad, fan-split";
  ASSERT_EQ(m.materials.size(), 3u);
  // The crate's Kd times the texture's mean linear colour: (0 + 1) / 2.
  EXPECT_NEAR(m.materials[2].reflectance.x, 1.2f * 0.5f, 1e-5f);

  ModelOptions o;
  o.emit.push_back(parse_emit_rule("Lamp*=12"));
  const SceneDescription d = model_to_scene(m, o);
  const Hierarchy h = build_hierarchy(d);
  EXPECT_EQ(h.triangles.size(), 6u);
  int pures = 0, composites = 0;
  for (const SceneObject& ob : h.objects) {
    pures += ob.kind == ObjectKind::Pure;
    composites += ob.kind == ObjectKind::Composite;
    if (ob.name == "lamp: LampShade") {
      // 12 x the shade's colour scaled to a largest channel of 1.
      EXPECT_NEAR(ob.material.emission.x, 12.0f, 1e-5f);
      EXPECT_NEAR(ob.material.emission.z, 12.0f * 0.4f / 0.9f, 1e-4f);
    }
  }
  EXPECT_EQ(composites, 3);
  EXPECT_EQ(pures, 4) << "floor, lamp, and the crate's two materials";
}

TEST_F(ModelFiles, NothingEmittingOrARuleMatchingNothingNamesTheOption) {
  write("room.mtl", kRoomMtl);
  const Model m = read_obj_file(write("room.obj", kRoomObj), SourceLoc{});
  try {
    model_to_scene(m, {});
    ADD_FAILURE() << "no emitter accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--emit"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("LampShade"), std::string::npos) << e.what();
  }
  ModelOptions o;
  o.emit.push_back(parse_emit_rule("Sun=5"));
  EXPECT_THROW(model_to_scene(m, o), Error);
  EXPECT_THROW(parse_emit_rule("Lamp"), Error);
  EXPECT_THROW(parse_emit_rule("Lamp=-1"), Error);
  EXPECT_THROW(parse_emit_rule("=3"), Error);
}

TEST_F(ModelFiles, ObjEmissionComesFromKeAndAMissingLibraryIsAWarning) {
  const std::string obj = write("lit.obj", "mtllib nosuch.mtl\nmtllib lit.mtl\nv 0 0 0\nv 1 0 0\n"
                                           "v 0 1 0\nusemtl Light\nf 1 2 3\n");
  write("lit.mtl", "newmtl Light\nKd 0 0 0\nKe 3 2 1\n");
  const SceneDescription d = read_scene_file(obj);
  ASSERT_EQ(d.objects.size(), 3u);
  EXPECT_EQ(d.objects[2].material.emission, Vec3(3, 2, 1));
}

TEST_F(ModelFiles, BadObjFilesEndInOneError) {
  for (const char* bad : {"v 0 0 0\nv 1 0 0\nf 1 2 7\n", "v 0 0 0\nv 1 0 0\nv 1e39 0 0\nf 1 2 3\n",
                          "v 1 2 3\n", "", "f -5 -6 -7\n"}) {
    EXPECT_THROW(parse_obj_text(bad, "", "bad.obj"), Error) << bad;
  }
}

std::string ply_header(const char* format, int vertices, int faces) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment a square\nelement vertex " +
         std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\n"
         "property uchar red\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

template <typename T>
void put(std::string& s, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof v);
  if (big == (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof b);
  s.append(b, sizeof b);
}

TEST_F(ModelFiles, PlyAsciiAndBinaryOfBothOrdersGiveTheSameTriangles) {
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::string ascii = ply_header("ascii", 4, 1);
  for (auto& p : v) ascii += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 7\n";
  ascii += "4 0 1 2 3\n";
  std::vector<Model> models{parse_ply(ascii, "sq.ply")};
  for (bool big : {false, true}) {
    std::string bin = ply_header(big ? "binary_big_endian" : "binary_little_endian", 4, 1);
    for (auto& p : v) {
      for (float c : p) put(bin, c, big);
      bin += char(7);
    }
    bin += char(4);
    for (int32_t i : {0, 1, 2, 3}) put(bin, i, big);
    models.push_back(parse_ply(bin, "sq.ply"));
  }
  for (const Model& m : models) {
    ASSERT_EQ(m.groups.size(), 1u);
    ASSERT_EQ(m.groups[0].triangles.size(), 2u);
    EXPECT_EQ(m.groups[0].triangles[1][2], Vec3(0, 1, 0));
    EXPECT_EQ(m.groups[0].name, "sq");
  }
}

TEST_F(ModelFiles, BadPlyFilesEndInOneErrorWithoutAllocatingTheirCounts) {
  const std::string huge = ply_header("binary_little_endian", 2000000000, 2000000000) + "abc";
  for (const std::string& bad :
       {huge, ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 9\n",
        ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 0 1\n", std::string("ply\nformat ascii 1.0\n"),
        std::string("plyformat"), ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 zero 1\n0 1 0 1\n3 0 1 2\n",
        std::string("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")}) {
    EXPECT_THROW(parse_ply(bad, "bad.ply"), Error) << bad.substr(0, 60);
  }
}

TEST_F(ModelFiles, ADescriptionFileMayNameAModelAsAPuresGeometry) {
  write("room.mtl", kRoomMtl);
  write("room.obj", kRoomObj);
  const std::string des = write("scene.des", "\"with a model\"\nObject \"all\" Pure { Reflectivity 0.5 "
                                              "Color <1 1 1> Emission 1 File \"room.obj\" }\n");
  const Hierarchy h = build_hierarchy(parse_scene_file(des));
  EXPECT_EQ(h.triangles.size(), 6u);
  EXPECT_EQ(h.objects[0].material.emission, Vec3(1.0f));
}

}  // namespace
}  // namespace rad
