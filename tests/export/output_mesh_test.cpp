// The output mesh is built incrementally for rad serve's snapshots, yet exactly as a whole build
// (make_output_mesh, what `rad` writes) lays it out.
#include "export/output_mesh.h"

#include <gtest/gtest.h>

#include "../serve/serve_scene.h"
#include "solver/edits.h"
#include "solver/solver.h"

namespace rad {
namespace {

void expect_same_as_a_whole_build(const OutputMeshBuilder& builder, const MeshGeometry& g,
                                  const SolverState& s) {
  const OutputMesh want = make_output_mesh(s, true);
  EXPECT_EQ(g.position, want.position());
  EXPECT_EQ(g.indices, want.indices());
  EXPECT_EQ(g.face_polygon, want.face_polygon());
  OutputMesh got;
  builder.values(s, ambient_radiosity(s.energy, s.solution), got);
  EXPECT_EQ(got.radiosity, want.radiosity);
  EXPECT_EQ(got.display, want.display);
  EXPECT_EQ(got.irradiance, want.irradiance);
  ASSERT_EQ(got.irradiance.size(), got.radiosity.size());
  // B = E + rho H at the first polygon's own vertices, which come first.
  const Material& m = s.solution.material_of(0);
  for (uint32_t v = 0; v < s.solution.mesh.polygons[0].vertex_count(); ++v)
    EXPECT_EQ(got.radiosity[v], m.emission + m.reflectance * got.irradiance[v]);
}

TEST(OutputMesh, TheIncrementalBuildIsTheWholeBuildShotAfterShot) {
  const Hierarchy h = build_hierarchy(testing::serve_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, testing::serve_options());
  OutputMeshBuilder builder;
  bool changed = false;
  auto g = builder.update(s, &changed);
  EXPECT_TRUE(changed);
  expect_same_as_a_whole_build(builder, *g, s);
  for (int i = 0; i < 6; ++i) {
    step(s, *vis);
    g = builder.update(s, &changed);
    expect_same_as_a_whole_build(builder, *g, s);
  }
  // Nothing split: the same geometry, shared.
  const auto again = builder.update(s, &changed);
  EXPECT_FALSE(changed);
  EXPECT_EQ(again, g);
  // One polygon split: new geometry, still the whole build's.
  ASSERT_GT(force_subdivide(edit_context(s), 0, *vis), 0u);
  g = builder.update(s, &changed);
  EXPECT_TRUE(changed);
  EXPECT_NE(g, again);
  expect_same_as_a_whole_build(builder, *g, s);
}

TEST(OutputMesh, DisplayAddsTheAmbientTermTimesReflectanceOnlyWhenAsked) {
  const Hierarchy h = build_hierarchy(testing::serve_scene());
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, testing::serve_options());
  for (int i = 0; i < 3; ++i) step(s, *vis);
  const OutputMesh plain = make_output_mesh(s, false), lifted = make_output_mesh(s, true);
  EXPECT_EQ(plain.display, plain.radiosity);
  EXPECT_EQ(lifted.radiosity, plain.radiosity);
  const Vec3 ambient = ambient_radiosity(s.energy, s.solution);
  ASSERT_GT(max_component(ambient), 0.0f);
  for (size_t v = 0; v < plain.radiosity.size(); ++v) {
    EXPECT_GT(max_component(lifted.display[v] - plain.display[v]), 0.0f) << "vertex " << v;
    EXPECT_LE(max_component(lifted.display[v] - plain.display[v]),
              max_component(ambient) * (1.0f + 1e-5f))
        << "vertex " << v;
  }
}

}  // namespace
}  // namespace rad
