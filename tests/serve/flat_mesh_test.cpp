// Snapshots flatten the mesh incrementally, yet exactly as `rad` writes it (make_output_mesh).
#include "serve/flat_mesh.h"

#include <gtest/gtest.h>

#include "export/output_mesh.h"
#include "serve_scene.h"
#include "solver/edits.h"
#include "solver/solver.h"

namespace rad {
namespace {

void expect_same_as_output_mesh(const FlatMesh& flat, const SnapshotGeometry& g,
                                const SolverState& s) {
  const OutputMesh want = make_output_mesh(s, true);
  EXPECT_EQ(g.position, want.position);
  EXPECT_EQ(g.indices, want.indices);
  EXPECT_EQ(g.face_polygon, want.face_polygon);
  std::vector<Vec3> radiosity, display;
  flat.values(s, ambient_radiosity(s), radiosity, display);
  // Equal up to rounding: the compiler may fuse a multiply-add in one place and not the other.
  auto expect_near = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      ASSERT_LE(max_component(glm::abs(a[i] - b[i])), 1e-6f * (1.0f + max_component(b[i])))
          << "vertex " << i;
    }
  };
  expect_near(radiosity, want.radiosity);
  expect_near(display, want.display);
}

TEST(FlatMesh, MatchesTheWrittenMeshShotAfterShot) {
  const Hierarchy h = build_hierarchy(testing::serve_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, testing::serve_options());
  FlatMesh flat;
  bool changed = false;
  auto g = flat.update(s, &changed);
  EXPECT_TRUE(changed);
  expect_same_as_output_mesh(flat, *g, s);
  for (int i = 0; i < 6; ++i) {
    step(s, *vis);
    g = flat.update(s, &changed);
    expect_same_as_output_mesh(flat, *g, s);
  }
  // Nothing split: the same geometry, shared.
  const auto again = flat.update(s, &changed);
  EXPECT_FALSE(changed);
  EXPECT_EQ(again, g);
  // One polygon split: new geometry, still the written mesh.
  ASSERT_GT(force_subdivide(s, 0, *vis), 0u);
  g = flat.update(s, &changed);
  EXPECT_TRUE(changed);
  EXPECT_NE(g, again);
  expect_same_as_output_mesh(flat, *g, s);
}

}  // namespace
}  // namespace rad
