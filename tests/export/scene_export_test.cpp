// rad convert's writers: a scene written in each format and read back keeps its triangles and,
// where the format holds them, its materials.
#include "export/scene_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "core/error.h"
#include "export/welded_mesh.h"
#include "hierarchy/hierarchy.h"
#include "scene/scene_file.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// Every triangle with its material, in an order that does not depend on the hierarchy: what a
// conversion must keep.
using Face = std::tuple<std::array<float, 9>, std::array<float, 6>>;
std::vector<Face> faces(const Hierarchy& h, bool with_material) {
  std::vector<Face> out;
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    std::array<float, 9> c;
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 3; ++a) c[size_t(3 * k + a)] = h.triangles.corners[t][size_t(k)][a];
    }
    std::array<float, 6> m{};
    if (with_material) {
      const Material& mat = h.objects[size_t(h.triangles.object[t])].material;
      m = {mat.reflectance.x, mat.reflectance.y, mat.reflectance.z,
           mat.emission.x,    mat.emission.y,    mat.emission.z};
    }
    out.emplace_back(c, m);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void expect_same(const std::vector<Face>& a, const std::vector<Face>& b, float tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    for (size_t k = 0; k < 9; ++k)
      ASSERT_NEAR(std::get<0>(a[i])[k], std::get<0>(b[i])[k], tolerance);
    for (size_t k = 0; k < 6; ++k) {
      ASSERT_NEAR(std::get<1>(a[i])[k], std::get<1>(b[i])[k], 1e-6f * (1 + std::get<1>(a[i])[k]));
    }
  }
}

class SceneExport : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("rad_scene_export_" + std::to_string(getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  Hierarchy round_trip(const std::string& scene_path, const std::string& name) {
    const SceneDescription d = read_scene_file(scene_path);
    const Hierarchy h = build_hierarchy(d);
    const std::string out = (dir / name).string();
    write_scene_file(out, d, h);
    ModelOptions o;
    o.require_emission = false;
    return build_hierarchy(read_scene_file(out, o));
  }
};

const std::string kCornell = RAD_SOURCE_DIR "/scenes/cornell_box.des";

TEST_F(SceneExport, EveryFormatKeepsTheTrianglesAndAllButPlyTheMaterials) {
  const std::vector<Face> original = faces(build_hierarchy(read_scene_file(kCornell)), true);
  for (const char* name : {"cornell.des", "cornell.obj", "cornell.gltf", "cornell.glb"}) {
    SCOPED_TRACE(name);
    // The description writes 9 significant digits; the models store floats.
    expect_same(original, faces(round_trip(kCornell, name), true), 1e-3f);
  }
  const std::vector<Face> bare = faces(build_hierarchy(read_scene_file(kCornell)), false);
  expect_same(bare, faces(round_trip(kCornell, "cornell.ply"), false), 1e-3f);
}

TEST_F(SceneExport, ADescriptionKeepsItsCopiesTransformsAndFlagsAsWritten) {
  const fs::path in = dir / "placed.des";
  std::ofstream(in) << R"("placed"
Object "lamp" Pure { Reflectivity 0 Color <1 1 1> Emission 5 Data { <0 1 0> <1 1 0> <0 1 1> } }
Object "card" Pure Translate <0 0.2 0> CastsShadows No {
  Reflectivity 0.5 Color <1 0.5 0.25> Emission 0 Data { <0 0 0> <0 0 1> <1 0 0> } }
Object "card 2" Copy "card" Rotate <0 1 0> 90 Scale 2
)";
  const SceneDescription d = read_scene_file(in.string());
  const fs::path out = dir / "placed_out.des";
  const std::vector<std::string> lost = write_scene_file(out.string(), d, build_hierarchy(d));
  EXPECT_TRUE(lost.empty());
  const SceneDescription back = read_scene_file(out.string());
  ASSERT_EQ(back.objects.size(), 3u);
  EXPECT_EQ(back.objects[2].copy_of, 1);
  EXPECT_EQ(back.objects[2].transforms.size(), 2u);
  EXPECT_EQ(back.objects[1].flags.casts_shadows, std::optional<bool>(false));
  expect_same(faces(build_hierarchy(d), true), faces(build_hierarchy(back), true), 1e-5f);
  // The other formats place the triangles and say what they dropped.
  const std::vector<std::string> obj_lost =
      write_scene_file((dir / "placed.obj").string(), d, build_hierarchy(d));
  EXPECT_GE(obj_lost.size(), 2u);
}

TEST_F(SceneExport, WeldingStoresEachCornerOnce) {
  const Hierarchy h = build_hierarchy(read_scene_file(kCornell));
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].kind != ObjectKind::Pure) continue;
    const WeldedMesh w = weld_pure(h, int32_t(i));
    ASSERT_EQ(w.indices.size(), 3u * h.objects[i].triangle_count);
    EXPECT_LT(w.position.size(), w.indices.size());  // every Cornell Pure is a closed quad or box
    for (size_t k = 0; k < w.indices.size(); ++k) {
      const uint32_t t = h.objects[i].first_triangle + uint32_t(k / 3);
      EXPECT_EQ(w.position[w.indices[k]], h.triangles.corners[t][k % 3]);
    }
  }
}

TEST_F(SceneExport, AnUnknownExtensionIsRefusedBeforeAnythingIsWritten) {
  const SceneDescription d = read_scene_file(kCornell);
  const fs::path out = dir / "cornell.fbx";
  EXPECT_THROW(write_scene_file(out.string(), d, build_hierarchy(d)), Error);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(SceneExport, AnEmissionOfItsOwnColourIsReportedForTheDescription) {
  const fs::path in = dir / "tinted.obj";
  std::ofstream(dir / "tinted.mtl") << "newmtl Lamp\nKd 0.8 0.8 0.8\nKe 10 9 8\n";
  std::ofstream(in) << "mtllib tinted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Lamp\nf 1 2 3\n";
  const SceneDescription d = read_scene_file(in.string());
  const std::vector<std::string> lost =
      write_scene_file((dir / "tinted.des").string(), d, build_hierarchy(d));
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_NE(lost[0].find("Lamp"), std::string::npos);
}

}  // namespace
}  // namespace rad
