// What model readers accept because other readers do (credit lines in PLY headers, Windows
// texture paths, UTF-16 OBJ files), what they say about what a model loses, and what stays an
// error: the cases tools/check_models found in Debian's assimp-testmodels, in small files.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "hierarchy/hierarchy.h"
#include "scene/model.h"
#include "scene/model_scene.h"
#include "scene/obj_reader.h"
#include "scene/ply_reader.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

class ModelLeniency : public ::testing::Test {
 protected:
  ModelLeniency() : dir(fs::temp_directory_path() / ("rad_lenient_" + std::to_string(getpid()))) {
    fs::create_directories(dir);
  }
  ~ModelLeniency() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& bytes) const {
    fs::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  }
  // A 1x1 PNG of one grey level at `name` (any extension: stb_image reads by content).
  void grey_png(const std::string& name, unsigned char level) const {
    fs::create_directories((dir / name).parent_path());
    const unsigned char px[3] = {level, level, level};
    ASSERT_TRUE(stbi_write_png((dir / name).c_str(), 1, 1, 3, px, 3));
  }
  fs::path dir;
};

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

const char* kTwoMaterials =
    "mtllib walls.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl Wall\nf 1 2 3\n"
    "usemtl Floor\nf 1 3 4\n";

TEST_F(ModelLeniency, CheckSummarisesAModelWithoutLampsAndWarnsHowToLightIt) {
  write("walls.mtl", "newmtl Wall\nKd 0.5 0.5 0.5\nnewmtl Floor\nKd 0.2 0.2 0.2\n");
  const Model m = read_obj_file(write("walls.obj", kTwoMaterials), SourceLoc{});
  EXPECT_THROW(model_to_scene(m, {}), Error) << "a solve still refuses it";
  ModelOptions check;
  check.require_emission = false;
  check.warn_unlit = true;
  ::testing::internal::CaptureStderr();
  const SceneDescription d = model_to_scene(m, check);
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warned.find("warning: nothing in this model emits light"), std::string::npos) << warned;
  EXPECT_NE(warned.find("--emit 'Wall=10'"), std::string::npos) << "its own material as example";
  EXPECT_NE(warned.find("Floor"), std::string::npos) << warned;
  const std::string summary = summarize(build_hierarchy(d));
  EXPECT_NE(summary.find("Triangles: 2"), std::string::npos) << summary;
  EXPECT_NE(summary.find("Materials: 2 (Wall, Floor)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("Textures: 0 read"), std::string::npos) << summary;
  EXPECT_NE(summary.find("Bounding box"), std::string::npos) << summary;
  // rad convert takes it silently.
  ModelOptions convert;
  convert.require_emission = false;
  ::testing::internal::CaptureStderr();
  model_to_scene(m, convert);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

const char* kPlyBody =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST_F(ModelLeniency, PlyCreditLineBeforeTheElementsIsSkippedWithAWarningNamingIt) {
  const std::string ply = std::string("ply\nformat ascii 1.0\nobj_info scanned\n") +
                          "Created by Blender3D 247 - www.blender.org, source file: \n" + kPlyBody;
  ::testing::internal::CaptureStderr();
  const Model m = parse_ply(ply, "wuson.ply");
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangle_count(), 1u);
  EXPECT_NE(warned.find("wuson.ply:4:1: warning: header line 'Created by Blender3D 247"),
            std::string::npos)
      << warned;
  EXPECT_EQ(warned.find("obj_info"), std::string::npos) << "standard: skipped silently";
  EXPECT_EQ(count(warned, "warning"), 1u) << warned;
}

TEST_F(ModelLeniency, PlyUnknownLineAmongTheElementsStaysALocatedError) {
  // "propery" could be a property the data holds: skipping it would misread every vertex.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\npropery float w\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  try {
    parse_ply(ply, "typo.ply");
    ADD_FAILURE() << "a misspelt property accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 5) << e.what();
    EXPECT_NE(e.message().find("propery"), std::string::npos) << e.what();
  }
}

TEST_F(ModelLeniency, PlyListLengthThatIsNoWholeNumberIsALocatedError) {
  // assimp's issue623.ply: a face list declared inside the vertex element, which the data
  // does not hold, so a coordinate is read as the list's length.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nproperty list uchar uint vertex_indices\nend_header\n"
      "1 2 3\n4.5 5 6\n7 8 9 10 11 12 13 14 15\n";
  try {
    parse_ply(ply, "issue623.ply");
    ADD_FAILURE() << "a fractional list length accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 10) << e.what();
    EXPECT_NE(e.message().find("not a whole number"), std::string::npos) << e.what();
  }
}

TEST_F(ModelLeniency, PlyNonFiniteNormalIsReadButANonFinitePositionIsNot) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(parse_ply(head + "0 0 0 nan\n1 0 0 0\n0 1 0 inf\n3 0 1 2\n", "n.ply").triangle_count(),
            1u);
  EXPECT_THROW(parse_ply(head + "0 0 0 0\n1 nan 0 0\n0 1 0 0\n3 0 1 2\n", "p.ply"), Error);
}

TEST_F(ModelLeniency, PointCloudsAreRefusedSayingTheyHaveNoSurface) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 1 1\n";
  try {
    parse_ply(ply, "points.ply");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("point cloud"), std::string::npos) << e.what();
  }
  try {
    parse_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n", "", "lines.obj");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("2 lines (l)"), std::string::npos) << e.what();
  }
}

TEST_F(ModelLeniency, ObjTexturePathsWithBackslashesAndOtherCaseAreFoundBesideTheFile) {
  grey_png("Wal67ar.JPG", 255);   // white: the material keeps its Kd
  grey_png("Maps/Wood.PNG", 0);   // black
  grey_png("mats/Stone.png", 0);  // beside the MTL file, not the OBJ
  grey_png("elsewhere.png", 0);   // named by a path from the exporter's machine
  write("walls.mtl",
        "newmtl Wall\nKd 0.5 0.5 0.5\nmap_Kd .\\wal67ar.jpg\n"
        "newmtl Floor\nKd 0.5 0.5 0.5\nmap_Kd maps\\wood.png\n"
        "newmtl Far\nKd 0.5 0.5 0.5\nmap_Kd C:\\Users\\someone\\textures\\elsewhere.png\n");
  write("mats/stone.mtl", "newmtl Stone\nKd 0.5 0.5 0.5\nmap_Kd stone.png\n");
  ::testing::internal::CaptureStderr();
  const Model m =
      read_obj_file(write("walls.obj",
                          "mtllib walls.mtl mats/stone.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                          "vt 0 0\nusemtl Wall\nf 1/1 2/1 3/1\nusemtl Floor\nf 1/1 2/1 3/1\n"
                          "usemtl Stone\nf 1/1 2/1 3/1\nusemtl Far\nf 1/1 2/1 3/1\n"),
                    SourceLoc{});
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "every texture found";
  ASSERT_EQ(m.materials.size(), 4u);
  for (const ModelMaterial& mat : m.materials) {
    EXPECT_EQ(mat.reflectance, mat.name == "Wall" ? Vec3(0.5f) : Vec3(0.0f)) << mat.name;
  }
  EXPECT_EQ(m.textures.read, 4u);
  EXPECT_EQ(m.textures.unread, 0u);
}

TEST_F(ModelLeniency, AMissingTextureIsWarnedOnceForAllTheMaterialsNamingIt) {
  write("walls.mtl",
        "newmtl A\nKd 0.5 0.5 0.5\nmap_Kd gone.png\nnewmtl B\nKd 0.5 0.5 0.5\nmap_Kd gone.png\n");
  ::testing::internal::CaptureStderr();
  const Model m = read_obj_file(write("walls.obj",
                                      "mtllib walls.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                      "usemtl A\nf 1 2 3\nusemtl B\nf 1 2 3\n"),
                                SourceLoc{});
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(count(warned, "warning"), 1u) << warned;
  EXPECT_NE(warned.find("gone.png (no such file); material 'A', 'B'"), std::string::npos) << warned;
  EXPECT_EQ(m.textures.unread, 2u);
}

TEST_F(ModelLeniency, ObjPointsAndLinesAreWarnedOncePerKindAtTheFirst) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (int i = 0; i < 50; ++i) obj += "l 1 2\n";  // lines 5..54
  for (int i = 0; i < 30; ++i) obj += "p 3\n";
  ::testing::internal::CaptureStderr();
  const Model m = parse_obj_text(obj, "", "mixed.obj");
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(count(warned, "warning"), 2u) << warned;
  EXPECT_NE(warned.find("mixed.obj:5:1: warning: 50 lines (l) skipped"), std::string::npos)
      << warned;
  EXPECT_NE(warned.find("mixed.obj:55:1: warning: 30 points (p) skipped"), std::string::npos)
      << warned;
}

TEST_F(ModelLeniency, ObjSaysOnceEachWhatItsMaterialsLose) {
  write("glass.mtl",
        "newmtl Glass\nKd 0.9 0.9 0.9\nd 0.3\nnewmtl Tinted\nKd 0.5 0.5 0.9\nTr 0.5\n"
        "newmtl Brick\nKd 0.6 0.3 0.2\nmap_Bump brick_n.png\nnewmtl Stone\nKd 0.5 0.5 0.5\n"
        "norm stone_n.png\nnewmtl Chrome\nKd 0.2 0.2 0.2\nKs 0.9 0.9 0.9\nNs 200\n"
        "newmtl Matte\nKd 0.7 0.7 0.7\nKs 0 0 0\nNs 10\nd 1\n");
  std::string obj = "mtllib glass.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\n";
  for (const char* mat : {"Glass", "Tinted", "Brick", "Stone", "Chrome", "Matte"})
    obj += std::string("usemtl ") + mat + "\nf 1 2 3\nf 1 2 3\n";
  ::testing::internal::CaptureStderr();
  const Model m = read_obj_file(write("glass.obj", obj), SourceLoc{});
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(m.triangle_count(), 12u);
  for (const char* said :
       {"warning: material 'Glass' (and 1 more) is partly transparent (d or Tr), which rad "
        "ignores: the surface is opaque",
        "warning: material 'Brick' (and 1 more) has a bump or normal map (map_Bump, bump or norm)",
        "warning: material 'Chrome' has a specular reflection (Ks, Ns, map_Ks), which rad "
        "ignores",
        "warning: the vertices' colours (v x y z r g b) are ignored"}) {
    EXPECT_NE(warned.find(said), std::string::npos) << said << "\n" << warned;
  }
  EXPECT_EQ(count(warned, "warning"), 4u) << "one per kind, Matte's defaults none: " << warned;
}

TEST_F(ModelLeniency, PlyVertexColoursAreSaidToBeIgnored) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\n";
  const std::string rest = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  ::testing::internal::CaptureStderr();
  parse_ply(header + "property uchar red\nproperty uchar green\nproperty uchar blue\n" + rest +
                "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n",
            "c.ply");
  std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warned.find("c.ply: warning: the vertices' colours (red, ...) are ignored"),
            std::string::npos)
      << warned;
  EXPECT_EQ(count(warned, "warning"), 1u) << warned;
  ::testing::internal::CaptureStderr();
  parse_ply(header + rest + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "plain.ply");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(ModelLeniency, ObjInUtf16OrWithAByteOrderMarkIsRead) {
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::string big = "\xFE\xFF", little = "\xFF\xFE";
  for (const char c : text) big += {'\0', c}, little += {c, '\0'};
  for (const std::string& obj : {big, little, "\xEF\xBB\xBF" + text}) {
    const Model m = parse_obj_text(obj, "", "utf.obj");
    ASSERT_EQ(m.triangle_count(), 1u);
    EXPECT_EQ(m.groups[0].triangles[0][1], Vec3(1, 0, 0)) << "the first vertex kept";
  }
}

TEST_F(ModelLeniency, ObjParseErrorsAreLocatedAtTheirLine) {
  try {
    parse_obj_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "", "zero.obj");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.loc().line, 4) << e.what();
  }
}

}  // namespace
}  // namespace rad
