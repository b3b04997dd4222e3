// rad's Cornell box, solved with the default options and the Embree backend, against the
// independent path-traced reference in scenes/reference/cornell_box.csv: mean error <= 1% of
// the mean radiosity, displayed radiosity Gouraud-interpolated.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "export/output_mesh.h"
#include "reference/compare.h"
#include "scene/parser.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

TEST(CornellReference, DefaultSolveWithinOnePercentMeanOfPathTracedReference) {
  const std::string root = RAD_SOURCE_DIR;
  const Hierarchy h = build_hierarchy(parse_scene_file(root + "/scenes/cornell_box.des"));
  const ReferenceSet reference =
      read_reference_csv_file(root + "/scenes/reference/cornell_box.csv");
  ASSERT_GT(reference.points.size(), 500u);

  const auto start = std::chrono::steady_clock::now();
  const auto backend = make_visibility_backend(BackendKind::Embree, h);
  SolverState state = make_solver_state(h, SolverOptions{});
  const StopReason stop = solve(state, *backend);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const OutputMesh mesh = make_output_mesh(state, /*ambient=*/false);

  const ComparisonReport r =
      compare_to_reference({mesh.position(), mesh.radiosity, mesh.indices(), mesh.face_polygon()},
                           reference, emitting_polygons(h));
  std::printf("rad (default options, Embree): %s after %lld shots, %zu faces, %.1f s\n",
              to_string(stop), (long long)state.shots.count, mesh.face_count(), seconds);
  std::fputs(format_report(r).c_str(), stdout);
  // Every point, for looking at where the error is.
  const std::string dump = std::string(RAD_BINARY_DIR) + "/cornell_reference_points.csv";
  std::ofstream out(dump);
  write_point_comparisons(out, r);
  std::printf("per-point values: %s\n", dump.c_str());
  EXPECT_EQ(r.outside, 0u);
  EXPECT_LE(r.all.mean_error, 0.01) << "target: mean error <= 1% of the mean radiosity";
  // The same bound without the light, whose exact emission dominates the mean: measured 1.26%
  // with 16 samples on every source, 0.79% with big sources sampled as finely as the mesh.
  EXPECT_LE(r.reflecting.mean_error, 0.01) << "reflecting surfaces alone";
}

// The same box with every triangle cut k x k (the same surfaces, so the same reference): the
// answer must not depend on the tessellation (mean <= 1%, |bias| <= 0.5% of the mean
// radiosity on the reflecting surfaces, stored radiosity). k = 4 runs in seconds; tools/bench
// takes k up to 24.
TEST(CornellReference, TessellatedBoxKeepsTheAnswer) {
  const std::string root = RAD_SOURCE_DIR;
  SceneDescription d = parse_scene_file(root + "/scenes/cornell_box.des");
  for (ObjectDescription& o : d.objects) {
    o.triangles = tessellate_triangles(o.triangles, 4);
    o.triangle_locs.assign(o.triangles.size(), SourceLoc{});
  }
  const Hierarchy h = build_hierarchy(d);
  const ReferenceSet reference =
      read_reference_csv_file(root + "/scenes/reference/cornell_box.csv");
  const auto backend = make_visibility_backend(BackendKind::Embree, h);
  SolverState state = make_solver_state(h, SolverOptions{});
  solve(state, *backend);
  const OutputMesh mesh = make_output_mesh(state, /*ambient=*/false);
  // The reference names the uncut box's polygons: each face is matched to the one it lies on.
  const Hierarchy uncut = build_hierarchy(parse_scene_file(root + "/scenes/cornell_box.des"));
  const std::vector<int32_t> face_polygon =
      assign_face_polygons(uncut.triangles, mesh.position(), mesh.indices());
  const ComparisonReport r =
      compare_to_reference({mesh.position(), mesh.radiosity, mesh.indices(), face_polygon},
                           reference, emitting_polygons(uncut));
  std::printf("Cornell box cut 4 x 4 (%zu triangles): %lld shots\n", h.triangles.size(),
              (long long)state.shots.count);
  std::fputs(format_report(r).c_str(), stdout);
  EXPECT_EQ(r.outside, 0u);
  EXPECT_LE(r.reflecting.mean_error, 0.01);
  EXPECT_LE(std::abs(r.reflecting.mean_signed_error), 0.005);
}

}  // namespace
}  // namespace rad
