// Model files as scenes: OBJ + MTL (tinyobjloader) and PLY, their materials, --emit, and the
// errors a user meets.
#include <gtest/gtest.h>
#include <unistd.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "hierarchy/hierarchy.h"
#include "scene/gltf_reader.h"
#include "scene/model.h"
#include "scene/model_scene.h"
#include "scene/obj_reader.h"
#include "scene/parser.h"
#include "scene/ply_reader.h"
#include "scene/scene_file.h"
#include "scene_texts.h"

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
  const std::string obj = write("lit.obj",
                                "mtllib nosuch.mtl\nmtllib lit.mtl\nv 0 0 0\nv 1 0 0\n"
                                "v 0 1 0\nusemtl Light\nf 1 2 3\n");
  write("lit.mtl", "newmtl Light\nKd 0 0 0\nKe 3 2 1\n");
  const SceneDescription d = read_scene_file(obj);
  ASSERT_EQ(d.objects.size(), 3u);
  EXPECT_EQ(d.objects[2].material.emission, Vec3(3, 2, 1));
}

TEST_F(ModelFiles, ObjMaterialLibrariesAreFoundOnAnyLineEvenBareOrLastOrCrlf) {
  // A bare `mtllib` names nothing; the library may be on the last line (no line end) or on a
  // CRLF line.
  write("last.mtl", "newmtl Light\nKd 0 0 0\nKe 3 2 1\n");
  const std::string last = write("last.obj",
                                 "mtllib\nmtllib \nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Light\n"
                                 "f 1 2 3\nmtllib last.mtl");
  EXPECT_EQ(read_scene_file(last).objects[2].material.emission, Vec3(3, 2, 1));
  const std::string crlf = write("crlf.obj",
                                 "mtllib last.mtl\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n"
                                 "usemtl Light\r\nf 1 2 3\r\n");
  EXPECT_EQ(read_scene_file(crlf).objects[2].material.emission, Vec3(3, 2, 1));
}

TEST_F(ModelFiles, BadObjFilesEndInOneError) {
  for (const char* bad : {"v 0 0 0\nv 1 0 0\nf 1 2 7\n", "v 0 0 0\nv 1 0 0\nv 1e39 0 0\nf 1 2 3\n",
                          "v 1 2 3\n", "", "f -5 -6 -7\n"}) {
    EXPECT_THROW(parse_obj_text(bad, "", "bad.obj"), Error) << bad;
  }
}

TEST_F(ModelFiles, ObjLinesEndAtAnyLineEndAsTinyobjloaderReadsThem) {
  // LF, CRLF and lone CR files give the same triangle; a statement rad drops (a skin weight
  // with a joint id beyond int, undefined behaviour in tinyobjloader) is dropped after a CR too.
  for (const char* end : {"\n", "\r\n", "\r"}) {
    const std::string e = end;
    const std::string obj =
        "v 0 0 0" + e + "v 1 0 0" + e + "v 0 1 0 " + "\rvw 1 5e17 1" + e + "f 1 2 3" + e;
    const Model m = parse_obj_text(obj, "", "endings.obj");
    EXPECT_EQ(m.triangle_count(), 1u) << int(end[0]);
  }
  // An error's line counts a CRLF as one line end.
  try {
    parse_obj_text("v 0 0 0\r\nv 1 0 0\r\nf 1 2 7\r\n", "", "crlf.obj");
    FAIL() << "an index beyond the vertices was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("crlf.obj"), std::string::npos) << e.what();
  }
}

std::string ply_header(const char* format, int vertices, int faces) {
  return std::string("ply\nformat ") + format + " 1.0\ncomment a square\nelement vertex " +
         std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\n"
         "property uchar red\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
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
  for (auto& p : v)
    ascii +=
        std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 7\n";
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
        std::string("plyformat"),
        ply_header("ascii", 3, 1) + "0 0 0 1\n1 0 zero 1\n0 1 0 1\n3 0 1 2\n",
        std::string("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
        // A second vertex element, without x, y and z: the faces must be checked against the
        // first one's count, or they read its columns beyond their end.
        std::string(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
            "property float z\nelement vertex 3\nproperty float w\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n0 0 0\n1\n2\n3\n3 0 1 2\n")}) {
    EXPECT_THROW(parse_ply(bad, "bad.ply"), Error) << bad.substr(0, 60);
  }
}

TEST_F(ModelFiles, ADescriptionFileMayNameAModelAsAPuresGeometry) {
  write("room.mtl", kRoomMtl);
  write("room.obj", kRoomObj);
  const std::string des = write("scene.des",
                                "\"with a model\"\nObject \"all\" Pure { Reflectivity 0.5 "
                                "Color <1 1 1> Emission 1 File \"room.obj\" }\n");
  const Hierarchy h = build_hierarchy(parse_scene_file(des));
  EXPECT_EQ(h.triangles.size(), 6u);
  EXPECT_EQ(h.objects[0].material.emission, Vec3(1.0f));
}

TEST_F(ModelFiles, ADescriptionBringsInAWholeModelWithItsMaterialsPlacedAndCopied) {
  write("room.mtl", kRoomMtl);
  write("room.obj", kRoomObj);
  const std::string des = write("scene.des", R"("models"
Object "light" Pure { Reflectivity 0 Color <1 1 1> Emission 5 Data { <0 9 0> <0 9 1> <1 9 0> } }
Object "room A" Model "room.obj" Translate <10 0 0> CastsShadows No
Object "room B" Copy "room A" Translate <0 0 10>
)");
  const SceneDescription d = parse_scene_file(des);
  ASSERT_EQ(d.roots.size(), 3u);
  const ObjectDescription& a = d.objects[size_t(d.roots[1])];
  EXPECT_EQ(a.kind, ObjectKind::Assembly);
  EXPECT_EQ(a.children.size(), 3u);  // the groups: floor, lamp, crate
  const Hierarchy h = build_hierarchy(d);
  EXPECT_EQ(h.triangles.size(), 1u + 2u * 6u);  // the light, and the room's 6 twice
  // The model's own materials, per (group, material), placed by the object's transforms.
  size_t floors = 0;
  for (const SceneObject& o : h.objects) {
    if (o.kind != ObjectKind::Pure || o.name != "floor: Floor") continue;
    ++floors;
    EXPECT_EQ(o.material.reflectance, Vec3(0.5f));
    EXPECT_FALSE(o.casts_shadows);  // the Model object's flag reaches its Pures
    EXPECT_GE(o.box.lo.x, 10.0f);
  }
  EXPECT_EQ(floors, 2u);
  // A Copy names the Model object, never one of its pieces of the same name (a group "floor").
  const std::string same = write("same.des", R"("same"
Object "light" Pure { Reflectivity 0 Color <1 1 1> Emission 5 Data { <0 9 0> <0 9 1> <1 9 0> } }
Object "floor" Model "room.obj"
Object "floor 2" Copy "floor" Translate <10 0 0>
)");
  EXPECT_EQ(build_hierarchy(parse_scene_file(same)).triangles.size(), 1u + 2u * 6u);
  // The model's two levels count towards the nesting limit, at the model's name.
  auto nested = [&](int assemblies) {
    std::string text = "\"deep\"\n";
    for (int i = 0; i < assemblies; ++i) text += "Object \"a\" Assembly {\n";
    text += "Object \"m\" Model \"room.obj\"\n";
    for (int i = 0; i < assemblies; ++i) text += "}\n";
    return write("deep.des", text);
  };
  EXPECT_NO_THROW(parse_scene_file(nested(250)));
  try {
    parse_scene_file(nested(255));
    FAIL() << "a model nested past the limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nested more than 256"), std::string::npos) << e.what();
    // Line 1 the name, 255 Assemblies, then the Model; column 18 is its file name.
    EXPECT_NE(std::string(e.what()).find("deep.des:257:18:"), std::string::npos) << e.what();
  }
  // What is not a model, and a Model in a Composite, are errors at the file's name.
  const std::string bad = write("bad.des", "\"bad\"\nObject \"m\" Model \"x.off\"\n");
  try {
    parse_scene_file(bad);
    FAIL() << "a .off named as a Model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.des:2:18"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_scene_file(write("bad2.des",
                                      "\"b\"\nObject \"c\" Composite { Object \"m\" "
                                      "Model \"room.obj\" }\n")),
               Error);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// One unit quad mesh placed by three nodes: moved, moved under a parent, mirrored.
std::string quad_gltf(const std::string& extra_node = "") {
  std::string buf;
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  buf.append(reinterpret_cast<const char*>(p), sizeof p);
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  buf.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 1, 3)" +
         extra_node + R"(]}],
    "nodes": [{"name": "near", "mesh": 0, "translation": [0, 0, 1]},
              {"name": "group", "translation": [10, 0, 0], "children": [2]},
              {"name": "far", "mesh": 0, "scale": [2, 2, 2]},
              {"name": "mirror", "mesh": 0, "scale": [-1, 1, 1]}],
    "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "materials": [{"name": "Lamp", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]},
                   "emissiveFactor": [1, 0.5, 0.25],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}],
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
         testing::base64(buf) + R"("}]})";
}

TEST_F(ModelFiles, GltfNodeTransformsComposeAndInstancesAreFlattened) {
  const Model m = parse_gltf(quad_gltf(), "quad.gltf", "");
  ASSERT_EQ(m.groups.size(), 3u) << "one group per placement";
  std::map<std::string, const ModelGroup*> by_name;
  for (const ModelGroup& g : m.groups) by_name[g.name] = &g;
  ASSERT_TRUE(by_name.count("near") && by_name.count("far") && by_name.count("mirror"));
  EXPECT_EQ(by_name["near"]->triangles[0][1], Vec3(1, 0, 1));
  EXPECT_EQ(by_name["far"]->triangles[0][1], Vec3(12, 0, 0)) << "parent translation after scale";
  // Mirrored: the corners are swapped so the front stays the front.
  const auto& t = by_name["mirror"]->triangles[0];
  const Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  EXPECT_GT(n.z, 0.0f);
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].reflectance, Vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(m.materials[0].emission, Vec3(8.0f, 4.0f, 2.0f)) << "factor x emissive strength";
}

TEST_F(ModelFiles, BadGltfFilesEndInOneError) {
  std::string cyclic = quad_gltf();
  cyclic.replace(cyclic.find("\"children\": [2]"), 15,
                 "\"children\": [1]");  // node 1 is its own child
  std::string doubling = quad_gltf();   // node 1 lists itself twice: 2^depth placements
  doubling.replace(doubling.find("\"children\": [2]"), 15, "\"children\": [1, 1]");
  std::string past = quad_gltf();
  past.replace(past.find("\"count\": 6"), 10, "\"count\": 9");
  for (const std::string& bad :
       {std::string("{"), std::string("glTF\x02\0\0\0", 8), cyclic, doubling, past,
        std::string(R"({"asset": {"version": "2.0"}, "scenes": []})")}) {
    EXPECT_THROW(parse_gltf(bad, "bad.gltf", ""), Error) << bad.substr(0, 40);
  }
  // External buffers are refused without a folder, and read only as regular files with one.
  std::string external = quad_gltf();
  const size_t uri = external.find("data:application");
  external.replace(uri, external.find('"', uri) - uri, "/dev/zero");
  EXPECT_THROW(parse_gltf(external, "ext.gltf", ""), Error);
  EXPECT_THROW(parse_gltf(external, "ext.gltf", dir.string()), Error);
}

TEST_F(ModelFiles, GltfOfVersionOneOrCompressedMeshesIsRefusedSayingHowToConvertIt) {
  auto message = [](const std::string& bytes) {
    try {
      parse_gltf(bytes, "old.gltf", "");
    } catch (const Error& e) {
      return e.message();
    }
    return std::string("accepted");
  };
  // glTF 1.0 keeps its meshes by id, in an object; tinygltf reads it as an empty 2.0 file.
  const std::string v1 = message(R"({"asset": {"version": "1.0"}, "meshes": {"box": {}}})");
  EXPECT_NE(v1.find("glTF 1.0"), std::string::npos) << v1;
  EXPECT_NE(v1.find("gltf-pipeline"), std::string::npos) << v1;
  const std::string glb1 = message(std::string("glTF\x01\0\0\0\x20\0\0\0", 12) + "{}");
  EXPECT_NE(glb1.find("glTF 1.0"), std::string::npos) << glb1;
  std::string draco = quad_gltf();
  draco.replace(draco.find("\"extensionsUsed\""), 0,
                "\"extensionsRequired\": [\"KHR_draco_mesh_compression\"],\n");
  const std::string d = message(draco);
  EXPECT_NE(d.find("KHR_draco_mesh_compression"), std::string::npos) << d;
  // A required extension about looks only is read without, once said.
  std::string looks = quad_gltf();
  looks.replace(looks.find("\"extensionsUsed\""), 0,
                "\"extensionsRequired\": [\"KHR_materials_pbrSpecularGlossiness\"],\n");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(parse_gltf(looks, "looks.gltf", "").groups.size(), 3u);
  const std::string warned = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warned.find("KHR_materials_pbrSpecularGlossiness is required but rad ignores it"),
            std::string::npos)
      << warned;
}

TEST_F(ModelFiles, GltfWithoutScenesPlacesEveryNodeNoOtherHolds) {
  std::string bytes = quad_gltf();
  const size_t from = bytes.find("\"scene\": 0");
  bytes.erase(from, bytes.find("\"nodes\": [{") - from);
  const Model m = parse_gltf(bytes, "noscene.gltf", "");
  std::vector<std::string> names;
  for (const ModelGroup& g : m.groups) names.push_back(g.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"far", "mirror", "near"}))
      << "far once, under its parent";
}

TEST_F(ModelFiles, GltfOfPointsAndLinesOnlyIsRefusedSayingSo) {
  std::string lines = quad_gltf();
  lines.replace(lines.find("\"indices\": 1,"), 0, "\"mode\": 1, ");
  try {
    parse_gltf(lines, "lines.gltf", "");
    ADD_FAILURE() << "lines accepted";
  } catch (const Error& e) {
    EXPECT_NE(e.message().find("only points and lines"), std::string::npos) << e.what();
  }
}

TEST_F(ModelFiles, GltfSpecularGlossinessMaterialsReflectTheirDiffuseColour) {
  std::string bytes = quad_gltf();
  bytes.replace(bytes.find("\"extensions\": {"), 15,
                "\"extensions\": {\"KHR_materials_pbrSpecularGlossiness\": "
                "{\"diffuseFactor\": [0.25, 0.5, 0.75, 1]}, ");
  const Model m = parse_gltf(bytes, "sg.gltf", "");
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].reflectance, Vec3(0.25f, 0.5f, 0.75f));
}

TEST_F(ModelFiles, AGltfSceneSolvesAsAModel) {
  const std::string path = write("quad.gltf", quad_gltf());
  const Hierarchy h = build_hierarchy(read_scene_file(path));
  EXPECT_EQ(h.triangles.size(), 6u);
  EXPECT_EQ(h.objects[0].name, "quad");
}

}  // namespace
}  // namespace rad
