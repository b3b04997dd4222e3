// Cross-checks: grid and Embree give brute force's answer on 100k random segments per scene,
// except segments passing within a tiny, exactly computed distance of a triangle's edge or plane.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "backend_params.h"
#include "hierarchy/auto_hierarchy.h"
#include "scenegen/scenegen.h"
#include "visibility/agreement.h"

namespace rad {
namespace {

constexpr size_t kSegments = 100000;
// Segments within ambiguity_limit of an edge or plane, where float rounding decides, may differ
// in at most this share.
constexpr double kMaxNearShare = 1e-4;

struct CrossScene {
  const char* name;
  SceneDescription (*make)();
};

const CrossScene kScenes[] = {
    {"cornell", [] { return make_cornell_box(20); }},  // 4.6k triangles, 8 Pures
    {"soup", [] { return make_triangle_soup(10000, 1); }},
    {"nested", [] { return generate_scene(SceneKind::Nested, 10000, 2); }},
    {"stadium", [] { return generate_scene(SceneKind::TeapotInStadium, 10000, 3); }},
    // The grid walks the automatic hierarchy's boxes (a binary tree of Assemblies) instead.
    {"room, automatic hierarchy",
     [] {
       return automatic_hierarchy(
           build_hierarchy(generate_scene(SceneKind::FurnishedRoom, 10000, 4)));
     }},
};

TEST(VisibilityCrossCheck, GridAndEmbreeAgreeWithBruteForce) {
  const BackendParam kChecked[] = {
      {BackendKind::Grid, true}, {BackendKind::Embree, true}, {BackendKind::Embree, false}};
  for (const CrossScene& scene : kScenes) {
    Hierarchy h = build_hierarchy(scene.make());
    const std::vector<Segment> s = random_segments(h, kSegments, 1234);
    auto brute = make_visibility_backend(BackendKind::Brute, h);
    size_t blocked = 0;
    for (const BackendParam& p : kChecked) {
      auto backend = make_visibility_backend(p.kind, h, {.packets = p.packets});
      const RayAgreement a = compare_rays(h, *brute, *backend, s);
      blocked = a.blocked;
      std::string label = backend_param_name({p, 0});
      std::printf(
          "[ cross    ] %-8s %6zu tris, %s: %zu segments (%zu blocked), %zu differ from "
          "brute force: %zu within %.3g of an edge/plane (farthest %.3g), %zu farther\n",
          scene.name, h.triangles.size(), label.c_str(), s.size(), blocked, a.mismatches.size(),
          a.near, ambiguity_limit(h), a.worst_near, a.far);
      for (const RayMismatch& m : a.mismatches) {
        if (m.ambiguity < ambiguity_limit(h)) continue;
        ADD_FAILURE() << scene.name << " " << label << ": segment (" << m.segment.origin.x << ", "
                      << m.segment.origin.y << ", " << m.segment.origin.z << ") + ("
                      << m.segment.direction.x << ", " << m.segment.direction.y << ", "
                      << m.segment.direction.z << "): brute force " << int(m.expected) << ", got "
                      << int(m.got) << ", " << m.ambiguity << " from any edge or plane";
      }
      EXPECT_LT(double(a.near), kMaxNearShare * double(s.size())) << scene.name << " " << label;
    }
    EXPECT_GT(blocked, s.size() / 20) << scene.name;
    EXPECT_LT(blocked, s.size() - s.size() / 20) << scene.name;
  }
}

}  // namespace
}  // namespace rad
