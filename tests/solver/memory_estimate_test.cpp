// The memory bound known before solving holds, and is near what a solve that splits everything
// it may actually uses.
#include "solver/memory_estimate.h"

#include <gtest/gtest.h>

#include "scene_builder.h"
#include "solver/solver.h"

namespace rad {
namespace {

double mesh_bytes(const SolverState& s) {
  double b = 0.0;
  for (const PolygonMesh& p : s.solution.mesh.polygons) {
    b += double(p.vertex_count()) * (sizeof(Vec3) + sizeof(VertexState)) +
         double(p.elements.size()) * sizeof(Element);
  }
  return b;
}

TEST(MemoryEstimate, BoundsTheGrowthOfASolveThatSplitsEverythingItMay) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0), Vec3(1), Vec3(0.5f), Vec3(0));
  testing::add_quad(d, "lamp", {0.4f, 0.4f, 0.99f}, {0.4f, 0.6f, 0.99f}, {0.6f, 0.6f, 0.99f},
                    {0.6f, 0.4f, 0.99f}, Vec3(0), Vec3(5));
  const Hierarchy h = build_hierarchy(d);
  SolverOptions o;
  o.subdivision_threshold = 0.0f;  // every lit element that may split does
  o.min_size = 0.02f;
  o.max_shots = 3;
  SolverState s = make_solver_state(h, o);
  const double before = mesh_bytes(s), bound = worst_case_growth_bytes(s);
  solve(s, *make_visibility_backend(BackendKind::Embree, h));
  const double grown = mesh_bytes(s) - before;
  std::printf("grew %.0f bytes of vertices and elements; bound %.0f\n", grown, bound);
  EXPECT_GT(grown, 0.0);
  EXPECT_LE(grown, bound);
  EXPECT_LE(bound, 6.0 * grown) << "the bound is far from a solve that splits nearly everything";
  EXPECT_GT(shot_log_bytes(s, 0), 1000.0);
}

}  // namespace
}  // namespace rad
