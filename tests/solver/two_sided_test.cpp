// A two-sided surface (`TwoSided Yes`, glTF doubleSided) receives, reflects and shoots on both
// sides, each its own radiosity: it solves as two one-sided surfaces back to back.
#include <gtest/gtest.h>

#include <string>

#include "scene/parser.h"
#include "scene_builder.h"
#include "visibility/backend.h"

namespace rad {
namespace {

// The screen facing the lamp, and turned over to face away (the same corners).
constexpr bool kNear = false, kFar = true;

// Radiosity integrated over triangles [first, last) of `s`'s hierarchy.
DVec3 integral(const SolverState& s, size_t first, size_t last) {
  DVec3 sum(0.0);
  for (size_t p = first; p < last; ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      const Vec3 b = s.solution.radiosity(p, el.v[0]) + s.solution.radiosity(p, el.v[1]) +
                     s.solution.radiosity(p, el.v[2]);
      sum += DVec3(b) * (double(el.area) / 3.0);
    });
  }
  return sum;
}

// The triangles of the Pure named `name`.
std::pair<size_t, size_t> triangles_of(const Hierarchy& h, const std::string& name) {
  for (const SceneObject& o : h.objects) {
    if (o.name == name) return {o.first_triangle, o.first_triangle + o.triangle_count};
  }
  ADD_FAILURE() << "no object " << name;
  return {0, 0};
}

TEST(TwoSided, APanelSolvesAsTwoOneSidedPanelsBackToBack) {
  const Hierarchy one = build_hierarchy(parse_scene_text(
      screen_room(screen_object("screen", "TwoSided Yes", kNear)), "two_sided.des"));
  const Hierarchy two = build_hierarchy(parse_scene_text(
      screen_room(screen_object("near", "", kNear) + screen_object("far", "", kFar)),
      "back_to_back.des"));
  const auto [first, last] = triangles_of(one, "screen");
  ASSERT_EQ(last - first, 4u) << "two triangles, each facing both ways";
  EXPECT_TRUE(one.objects[one.triangles.object[first]].two_sided);
  // The second half is the first turned over: same corners, opposite normals.
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(one.triangles.normal[first + 2 + i], -one.triangles.normal[first + i]);
    EXPECT_EQ(one.triangles.area[first + 2 + i], one.triangles.area[first + i]);
  }
  const auto vis_one = make_visibility_backend(BackendKind::Embree, one);
  const auto vis_two = make_visibility_backend(BackendKind::Embree, two);
  // Without the roulette and the intensity cut: the two layouts number their clusters apart, so
  // their shots draw differently, and that noise (0.4-0.5% on the far side's dim light) would
  // hide a real difference. Without it they agree within 0.01%.
  SolverOptions exact;
  exact.roulette = 0.0f;
  exact.intensity_cut = 0.0f;
  const SolverState a = testing::solve_shots(one, *vis_one, exact, 120);
  const SolverState b = testing::solve_shots(two, *vis_two, exact, 120);
  const auto [near_b, near_e] = triangles_of(two, "near");
  const auto [far_b, far_e] = triangles_of(two, "far");
  const DVec3 near_one = integral(a, first, first + 2), far_one = integral(a, first + 2, last);
  const DVec3 near_two = integral(b, near_b, near_e), far_two = integral(b, far_b, far_e);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(near_one[k] / near_two[k], 1.0, 0.001) << "channel " << k;
    EXPECT_NEAR(far_one[k] / far_two[k], 1.0, 0.001) << "channel " << k;
    // The far side has its own light: what comes over the screen, less than the near side's.
    EXPECT_GT(far_one[k], 0.02 * near_one[k]) << "channel " << k;
    EXPECT_LT(far_one[k], 0.8 * near_one[k]) << "channel " << k;
  }
  // The room beyond the screen is lit by both sides' light alike.
  const auto [x2_b, x2_e] = triangles_of(one, "x2");
  const auto [x2b_b, x2b_e] = triangles_of(two, "x2");
  const DVec3 wall_one = integral(a, x2_b, x2_e), wall_two = integral(b, x2b_b, x2b_e);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(wall_one[k] / wall_two[k], 1.0, 0.001);
}

TEST(TwoSided, OneSidedThePanelsBackIsNotThere) {
  const Hierarchy h = build_hierarchy(
      parse_scene_text(screen_room(screen_object("screen", "", kNear)), "one_sided.des"));
  const auto [first, last] = triangles_of(h, "screen");
  EXPECT_EQ(last - first, 2u);
  EXPECT_FALSE(h.objects[h.triangles.object[first]].two_sided);
  // `TwoSided No` below a two-sided Assembly: the nearest setting wins.
  const Hierarchy n = build_hierarchy(parse_scene_text(
      "\"s\"\nObject \"g\" Assembly TwoSided Yes {\n" + screen_object("a", "TwoSided No", kNear) +
          screen_object("b", "", kFar) + "}\n",
      "nested.des"));
  EXPECT_EQ(triangles_of(n, "a").second - triangles_of(n, "a").first, 2u);
  EXPECT_EQ(triangles_of(n, "b").second - triangles_of(n, "b").first, 4u);
}

}  // namespace
}  // namespace rad
