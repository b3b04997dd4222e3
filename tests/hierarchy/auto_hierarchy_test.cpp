// The automatic hierarchy: the same Pures regrouped into compact Composites and Assemblies of
// what is near, and nothing else changed.
#include "hierarchy/auto_hierarchy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <tuple>

#include "core/error.h"
#include "scene/parser.h"
#include "scenegen/scenegen.h"

namespace rad {
namespace {

// Each Pure as (name, material, triangles, flags), sorted: what regrouping must keep.
using PureKey =
    std::tuple<std::string, std::array<float, 6>, std::vector<std::array<float, 9>>, bool, bool>;
std::vector<PureKey> pures(const Hierarchy& h) {
  std::vector<PureKey> out;
  for (const SceneObject& o : h.objects) {
    if (o.kind != ObjectKind::Pure) continue;
    std::vector<std::array<float, 9>> t;
    for (uint32_t i = o.first_triangle; i < o.first_triangle + o.triangle_count; ++i) {
      std::array<float, 9> c;
      for (int k = 0; k < 9; ++k) c[size_t(k)] = h.triangles.corners[i][size_t(k / 3)][k % 3];
      t.push_back(c);
    }
    const Material& m = o.material;
    out.emplace_back(o.name,
                     std::array<float, 6>{m.reflectance.x, m.reflectance.y, m.reflectance.z,
                                          m.emission.x, m.emission.y, m.emission.z},
                     t, o.casts_shadows, o.receives_shadows);
  }
  std::sort(out.begin(), out.end());
  return out;
}

int depth(const Hierarchy& h, int32_t id) {
  int d = 0;
  for (int32_t c : h.objects[size_t(id)].children) d = std::max(d, depth(h, c));
  return d + 1;
}

TEST(AutoHierarchy, KeepsEveryPureWithItsMaterialTrianglesAndFlags) {
  SceneDescription d = generate_scene(SceneKind::Building, 20000, 3);
  d.objects[3].flags.casts_shadows = false;  // a flag set on one object, resolved onto its Pures
  const Hierarchy as_read = build_hierarchy(d);
  const Hierarchy automatic = build_hierarchy(d, HierarchyMode::Automatic);
  const Hierarchy flat = build_hierarchy(d, HierarchyMode::Flat);
  EXPECT_EQ(pures(as_read), pures(automatic));
  EXPECT_EQ(pures(as_read), pures(flat));
  EXPECT_EQ(automatic.triangles.size(), as_read.triangles.size());
  EXPECT_EQ(flat.roots.size(), 1u);
  EXPECT_EQ(flat.objects[size_t(flat.roots[0])].kind, ObjectKind::Composite);
}

TEST(AutoHierarchy, CompositesAreCompactAndTheTreeIsShallow) {
  const Hierarchy h =
      build_hierarchy(generate_scene(SceneKind::Building, 100000, 1), HierarchyMode::Automatic);
  size_t pures = 0, composites = 0;
  for (const SceneObject& o : h.objects) {
    pures += o.kind == ObjectKind::Pure;
    if (o.kind != ObjectKind::Composite) continue;
    ++composites;
    EXPECT_LE(o.children.size(), 32u);
    // No part is a room's shell: every part's box is at most half of its Composite's.
    for (int32_t c : o.children) {
      const Vec3 e = h.objects[size_t(c)].box.extent(), whole = o.box.extent();
      EXPECT_LT(e.x * e.y * e.z, 0.5f * whole.x * whole.y * whole.z + 1e-6f) << o.name;
    }
  }
  EXPECT_GT(composites, 0u);
  ASSERT_EQ(h.roots.size(), 1u);
  // A binary split of the Pures: about log2 of their number deep, not their number.
  EXPECT_LE(depth(h, h.roots[0]), 2 * int(std::ceil(std::log2(double(pures)))) + 2);
}

TEST(AutoHierarchy, IsDeterministic) {
  const SceneDescription d = generate_scene(SceneKind::FurnishedRoom, 8000, 2);
  const SceneDescription a = automatic_hierarchy(build_hierarchy(d));
  const SceneDescription b = automatic_hierarchy(build_hierarchy(d));
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].name, b.objects[i].name);
    EXPECT_EQ(a.objects[i].children, b.objects[i].children);
    EXPECT_EQ(a.objects[i].triangles, b.objects[i].triangles);
  }
}

// Every field of an object the program reads, but its name and source location.
auto fields(const SceneObject& o) {
  return std::tie(o.kind, o.parent, o.children, o.first_triangle, o.triangle_count, o.box.lo,
                  o.box.hi, o.material.reflectance, o.material.emission, o.casts_shadows,
                  o.receives_shadows, o.influence);
}

TEST(AutoHierarchy, PlacedStraightFromTheHierarchyIsWhatASecondBuildMakes) {
  // Regrouping reorders the first build's triangles instead of building the regrouped
  // description again: the same tree, boxes, flags and triangles (normals and areas included).
  SceneDescription d = generate_scene(SceneKind::FurnishedRoom, 8000, 2);
  d.objects[3].flags.casts_shadows = false;  // a Pure's own flag survives regrouping
  for (const SceneDescription& scene : {d, generate_scene(SceneKind::Building, 6400, 1)}) {
    const Hierarchy h = build_hierarchy(scene);
    for (const HierarchyMode mode : {HierarchyMode::Automatic, HierarchyMode::Flat}) {
      const Hierarchy a = regrouped_hierarchy(h, mode);
      const Hierarchy b = build_hierarchy(mode == HierarchyMode::Automatic ? automatic_hierarchy(h)
                                                                           : flat_hierarchy(h));
      ASSERT_EQ(a.objects.size(), b.objects.size());
      EXPECT_EQ(a.roots, b.roots);
      for (size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_TRUE(fields(a.objects[i]) == fields(b.objects[i])) << a.objects[i].name;
        EXPECT_EQ(a.objects[i].name, b.objects[i].name);
      }
      EXPECT_EQ(a.triangles.corners, b.triangles.corners);
      EXPECT_EQ(a.triangles.normal, b.triangles.normal);
      EXPECT_EQ(a.triangles.area, b.triangles.area);
      EXPECT_EQ(a.triangles.object, b.triangles.object);
      EXPECT_EQ(a.bounds.lo, b.bounds.lo);
      EXPECT_EQ(a.bounds.hi, b.bounds.hi);
    }
  }
}

TEST(AutoHierarchy, RefusesToDropALightsListAndNamesTheOption) {
  const Hierarchy h = build_hierarchy(generate_scene(SceneKind::Building, 3200, 1, 1));
  try {
    automatic_hierarchy(h);
    FAIL() << "a building with Lights lists was regrouped";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--hierarchy file"), std::string::npos) << e.what();
  }
  EXPECT_THROW(flat_hierarchy(h), Error);
}

TEST(AutoHierarchy, ModelsDefaultToItAndDescriptionsToTheFile) {
  EXPECT_EQ(default_hierarchy_mode("room.obj"), HierarchyMode::Automatic);
  EXPECT_EQ(default_hierarchy_mode("room.GLB"), HierarchyMode::Automatic);
  EXPECT_EQ(default_hierarchy_mode("room.des"), HierarchyMode::AsRead);
  EXPECT_EQ(parse_hierarchy_mode("flat"), HierarchyMode::Flat);
  EXPECT_THROW(parse_hierarchy_mode("bvh"), Error);
}

}  // namespace
}  // namespace rad
