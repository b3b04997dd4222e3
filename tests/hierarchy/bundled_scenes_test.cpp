// The scenes shipped in scenes/: each parses and builds, and each has the geometry its comment
// promises (the Cornell box faces inward, the furnace box is closed, ...).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "scene/parser.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(RAD_SOURCE_DIR) / "scenes";

Hierarchy load(const std::string& name) {
  return build_hierarchy(parse_scene_file((kScenes / name).string()));
}

Vec3 centroid(const std::array<Vec3, 3>& t) { return (t[0] + t[1] + t[2]) / 3.0f; }

// Sum of area-weighted normals of a closed surface is zero.
Vec3 vector_area(const Hierarchy& h, uint32_t first, uint32_t count) {
  DVec3 sum(0.0);
  for (uint32_t t = first; t < first + count; ++t) {
    sum += DVec3(h.triangles.normal[t]) * double(h.triangles.area[t]);
  }
  return Vec3(sum);
}

int find_object(const Hierarchy& h, const std::string& name, int parent = -2) {
  for (size_t i = 0; i < h.objects.size(); ++i) {
    if (h.objects[i].name == name && (parent == -2 || h.objects[i].parent == parent)) {
      return static_cast<int>(i);
    }
  }
  ADD_FAILURE() << "no object " << name;
  return 0;
}

TEST(BundledScenes, EveryDescriptionParsesAndBuilds) {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() == ".des") scenes.push_back(entry.path());
  }
  std::sort(scenes.begin(), scenes.end());
  EXPECT_GE(scenes.size(), 4u);
  for (const fs::path& p : scenes) {
    SCOPED_TRACE(p.filename().string());
    Hierarchy h = build_hierarchy(parse_scene_file(p.string()));
    EXPECT_GT(h.triangles.size(), 0u);
    EXPECT_EQ(h.dropped_degenerate, 0u);
    EXPECT_FALSE(h.bounds.empty());
    bool emits = false;
    for (const SceneObject& o : h.objects) {
      if (o.kind == ObjectKind::Pure && max_component(o.material.emission) > 0) emits = true;
    }
    EXPECT_TRUE(emits) << "a scene without light is black";
  }
}

TEST(CornellBox, HasThePublishedBoundsInMillimetres) {
  Hierarchy h = load("cornell_box.des");
  EXPECT_EQ(h.bounds.lo, Vec3(0, 0, 0));
  EXPECT_FLOAT_EQ(h.bounds.hi.x, 556.0f);
  EXPECT_FLOAT_EQ(h.bounds.hi.y, 548.8f);
  EXPECT_FLOAT_EQ(h.bounds.hi.z, 559.2f);
  EXPECT_EQ(h.triangles.size(), 32u);
}

TEST(CornellBox, HasTheRoomLightAndTwoFiveFacedBlocks) {
  Hierarchy h = load("cornell_box.des");
  ASSERT_EQ(h.roots.size(), 1u);
  const SceneObject& room = h.objects[h.roots[0]];
  EXPECT_EQ(room.kind, ObjectKind::Assembly);
  int blocks = 0;
  for (int32_t c : room.children) {
    const SceneObject& o = h.objects[c];
    if (o.kind == ObjectKind::Composite) {
      ++blocks;
      EXPECT_EQ(o.children.size(), 5u) << o.name;
      EXPECT_EQ(o.triangle_count, 10u) << o.name;
    }
  }
  EXPECT_EQ(blocks, 2);
}

TEST(CornellBox, LightHangsHalfAMillimetreBelowTheCeilingFacingDown) {
  Hierarchy h = load("cornell_box.des");
  const SceneObject& light = h.objects[find_object(h, "light")];
  EXPECT_GT(max_component(light.material.emission), 0.0f);
  EXPECT_FLOAT_EQ(light.box.lo.y, 548.3f);
  EXPECT_FLOAT_EQ(light.box.hi.y, 548.3f);
  EXPECT_EQ(light.box.lo.x, 213.0f);
  EXPECT_EQ(light.box.hi.x, 343.0f);
  EXPECT_EQ(light.box.lo.z, 227.0f);
  EXPECT_EQ(light.box.hi.z, 332.0f);
  for (uint32_t t = light.first_triangle; t < light.first_triangle + light.triangle_count; ++t) {
    EXPECT_NEAR(h.triangles.normal[t].y, -1.0f, 1e-6f);
  }
  for (const SceneObject& o : h.objects) {
    if (o.kind == ObjectKind::Pure && o.name != "light") {
      EXPECT_EQ(max_component(o.material.emission), 0.0f) << o.name;
    }
  }
}

TEST(CornellBox, EveryFaceFrontLooksIntoTheBoxAndAwayFromTheBlocks) {
  Hierarchy h = load("cornell_box.des");
  const Vec3 room_center(278.0f, 274.4f, 279.6f);
  for (const SceneObject& o : h.objects) {
    if (o.kind != ObjectKind::Composite) continue;
    const Vec3 block_center = o.box.center();
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
      Vec3 c = centroid(h.triangles.corners[t]);
      EXPECT_GT(glm::dot(h.triangles.normal[t], c - block_center), 0.0f)
          << o.name << " triangle " << t;
    }
  }
  for (size_t i = 0; i < h.objects.size(); ++i) {
    const SceneObject& o = h.objects[i];
    if (o.kind != ObjectKind::Pure || h.objects[o.parent].kind == ObjectKind::Composite) continue;
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
      Vec3 c = centroid(h.triangles.corners[t]);
      EXPECT_GT(glm::dot(h.triangles.normal[t], room_center - c), 0.0f)
          << o.name << " triangle " << t;
    }
  }
}

TEST(CornellBox, UsesRedLeftAndGreenRightWallsSeenFromTheCamera) {
  Hierarchy h = load("cornell_box.des");
  const SceneObject& red = h.objects[find_object(h, "left wall (red)")];
  const SceneObject& green = h.objects[find_object(h, "right wall (green)")];
  // The camera at z = -800 looks toward +z with y up, so +x is on its left.
  EXPECT_GT(red.box.lo.x, 500.0f);
  EXPECT_EQ(green.box.hi.x, 0.0f);
  EXPECT_GT(red.material.reflectance.r, red.material.reflectance.g);
  EXPECT_GT(green.material.reflectance.g, green.material.reflectance.r);
  EXPECT_NEAR(h.objects[find_object(h, "floor")].material.reflectance.g, 0.73f, 1e-6f);
}

TEST(FurnaceBox, IsAClosedCubeFacingInwardWithUniformMaterial) {
  Hierarchy h = load("furnace_box.des");
  EXPECT_EQ(h.triangles.size(), 12u);
  Vec3 closed = vector_area(h, 0, static_cast<uint32_t>(h.triangles.size()));
  EXPECT_NEAR(glm::length(closed), 0.0f, 1e-6f);
  const Vec3 center = h.bounds.center();
  float total_area = 0.0f;
  for (uint32_t t = 0; t < h.triangles.size(); ++t) {
    EXPECT_GT(glm::dot(h.triangles.normal[t], center - centroid(h.triangles.corners[t])), 0.0f);
    total_area += h.triangles.area[t];
    const Material& m = h.objects[h.triangles.object[t]].material;
    EXPECT_EQ(m.reflectance, Vec3(0.5f));
    EXPECT_EQ(m.emission, Vec3(1.0f));
  }
  EXPECT_FLOAT_EQ(total_area, 6.0f);
}

TEST(ParallelSquares, FaceEachOtherOneUnitApart) {
  Hierarchy h = load("parallel_squares.des");
  const SceneObject& e = h.objects[find_object(h, "emitter")];
  const SceneObject& r = h.objects[find_object(h, "receiver")];
  EXPECT_EQ(vector_area(h, e.first_triangle, e.triangle_count), Vec3(0, 0, 1));
  EXPECT_EQ(vector_area(h, r.first_triangle, r.triangle_count), Vec3(0, 0, -1));
  EXPECT_EQ(e.box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(r.box.hi, Vec3(1, 1, 1));
  EXPECT_EQ(e.material.emission, Vec3(1.0f));
  EXPECT_EQ(r.material.emission, Vec3(0.0f));
}

TEST(OriginalStyle, NestsAssembliesCompositesAndPuresFromOffFiles) {
  Hierarchy h = load("original_style.des");
  std::map<ObjectKind, int> kinds;
  for (const SceneObject& o : h.objects) ++kinds[o.kind];
  EXPECT_GE(kinds[ObjectKind::Assembly], 3);
  EXPECT_EQ(kinds[ObjectKind::Composite], 2);
  EXPECT_GE(kinds[ObjectKind::Pure], 10);
  EXPECT_GE(h.triangles.size(), 200u);
  EXPECT_LE(h.triangles.size(), 600u);
  int table = find_object(h, "table");
  EXPECT_EQ(h.objects[table].kind, ObjectKind::Composite);
  EXPECT_EQ(h.objects[h.objects[table].parent].kind, ObjectKind::Assembly);
  for (int32_t c : h.objects[table].children) {
    EXPECT_EQ(h.objects[c].kind, ObjectKind::Pure);
    // Each box is closed and faces outward.
    const SceneObject& part = h.objects[c];
    EXPECT_NEAR(glm::length(vector_area(h, part.first_triangle, part.triangle_count)), 0.0f, 1e-5f);
    for (uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
      EXPECT_GT(
          glm::dot(h.triangles.normal[t], centroid(h.triangles.corners[t]) - part.box.center()),
          0.0f);
    }
  }
}

TEST(OriginalStyle, RoomShellFacesInwardAndLightFacesDown) {
  Hierarchy h = load("original_style.des");
  const Vec3 center(0.0f, 1.5f, 0.0f);
  int shell = find_object(h, "shell");
  const SceneObject& s = h.objects[shell];
  for (uint32_t t = s.first_triangle; t < s.first_triangle + s.triangle_count; ++t) {
    EXPECT_GT(glm::dot(h.triangles.normal[t], center - centroid(h.triangles.corners[t])), 0.0f);
  }
  const SceneObject& light = h.objects[find_object(h, "light")];
  for (uint32_t t = light.first_triangle; t < light.first_triangle + light.triangle_count; ++t) {
    EXPECT_NEAR(h.triangles.normal[t].y, -1.0f, 1e-6f);
  }
  EXPECT_LT(light.box.hi.y, h.bounds.hi.y);
}

}  // namespace
}  // namespace rad
