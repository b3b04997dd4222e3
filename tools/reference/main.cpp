// rad-reference: the independent path-traced radiosity reference for a scene, and the
// comparison of a rad output file against it.
//
// Regenerate the committed Cornell box reference (scenes/reference/cornell_box.csv):
//   nice build/tools/rad-reference scenes/cornell_box.des -o scenes/reference/cornell_box.csv
// (defaults: --points 1500 --min-per-triangle 8 --seed 1 --target 0.002; 54M paths, 85 s of CPU,
// 2.5 min on 2 busy cores).
// Compare a rad run with it:
//   build/rad scenes/cornell_box.des out/cornell.ply
//   build/tools/rad-reference scenes/cornell_box.des --compare out/cornell.ply
//       --reference scenes/reference/cornell_box.csv
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "hierarchy/hierarchy.h"
#include "reference/buried_points.h"
#include "reference/compare.h"
#include "reference/path_tracer.h"
#include "reference/ply_reader.h"
#include "reference/reference_points.h"
#include "scene/parser.h"

namespace {

int compare(const rad::Hierarchy& h, const std::string& reference_path,
            const std::string& mesh_path, const std::string& points_path,
            const std::vector<float>& ambient) {
  using namespace rad;
  const ReferenceSet ref = read_reference_csv_file(reference_path);
  PlyMesh mesh = read_radiosity_ply(mesh_path);
  const std::vector<int32_t> polygon =
      assign_face_polygons(h.triangles, mesh.position, mesh.indices);
  if (!ambient.empty()) {
    // The displayed radiosity, as rad's display makes it: B + reflectance x ambient. Each
    // vertex takes the reflectance of the polygon of a face using it (rad writes no vertex
    // shared by two polygons).
    const Vec3 amb(ambient[0], ambient[1], ambient[2]);
    std::vector<uint8_t> done(mesh.radiosity.size(), 0);
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
      const uint32_t v = mesh.indices[i];
      const int32_t p = polygon[i / 3];
      if (done[v] || p < 0) continue;
      done[v] = 1;
      const Material& m = h.objects[size_t(h.triangles.object[size_t(p)])].material;
      mesh.radiosity[v] += m.reflectance * amb;
    }
  }
  const RayScene scene(h.triangles);
  const std::vector<uint8_t> buried =
      buried_points(scene, h.triangles, ref.points, 1e-5f * h.bounds.diagonal());
  const ComparisonReport r = compare_to_reference(
      {mesh.position, mesh.radiosity, mesh.indices, polygon}, ref, emitting_polygons(h), buried);
  std::fputs(format_report(r).c_str(), stdout);
  if (!points_path.empty()) {
    std::ofstream out(points_path);
    write_point_comparisons(out, r);
    if (!out) throw Error(SourceLoc{points_path, 0, 0}, "cannot write the point comparisons");
  }
  return 0;
}

int generate(const rad::Hierarchy& h, const std::string& scene_path, const std::string& out_path,
             const rad::PointOptions& po, const rad::TraceOptions& to, int threads) {
  using namespace rad;
  ReferenceSet set;
  set.points = make_reference_points(h.triangles, po);
  std::fprintf(stderr, "%zu points on %zu triangles, %d threads\n", set.points.size(),
               h.triangles.size(), threads);
  size_t last = 0;
  TraceStats stats;
  set.values = estimate_radiosity(h, set.points, to, &stats, [&](size_t done, size_t total) {
    if (done * 20 / total != last * 20 / total || done == total) {
      std::fprintf(stderr, "\r%zu / %zu points", done, total);
      std::fflush(stderr);
    }
    last = done;
  });
  std::fputc('\n', stderr);
  set.comments = {
      fmt::format("rad reference radiosity for {} ({} points): B = E + rho H, path traced "
                  "(tools/reference/path_tracer.h)",
                  scene_path, set.points.size()),
      fmt::format("regenerate: nice build/tools/rad-reference {} -o {} --points {} "
                  "--min-per-triangle {} --seed {} --target {}{}{}",
                  scene_path, out_path, po.total, po.min_per_triangle, po.seed, to.target_stderr,
                  to.next_event ? "" : " --no-next-event",
                  to.max_bounces < 0 ? "" : fmt::format(" --max-bounces {}", to.max_bounces)),
      fmt::format("{} paths, {:.0f} s on {} threads; mean radiosity {:.6g} {:.6g} {:.6g}; "
                  "worst stderr {:.3f}% of the channel mean; {} points stopped at max samples",
                  stats.samples, stats.seconds, threads, stats.mean_radiosity.x,
                  stats.mean_radiosity.y, stats.mean_radiosity.z,
                  100.0 * stats.worst_relative_stderr, stats.points_at_max_samples),
      "triangle = rad polygon id; position = a + u (b - a) + v (c - a); stderr = standard error",
  };
  std::ofstream out(out_path);
  if (!out) throw Error(SourceLoc{out_path, 0, 0}, "cannot write the reference file");
  write_reference_csv(out, set);
  out.close();
  if (!out) throw Error(SourceLoc{out_path, 0, 0}, "cannot write the reference file");
  std::fprintf(stderr, "%s\n", set.comments[2].c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Path-traced radiosity reference for a rad scene, and comparison against it."};
  std::string scene_path, out_path, reference_path, mesh_path;
  rad::PointOptions po;
  rad::TraceOptions to;
  int threads = 0;
  app.add_option("SCENE", scene_path, "scene description (.des)")->required();
  app.add_option("-o,--output", out_path, "reference CSV to write");
  app.add_option("--points", po.total, "points over the scene, by area")->capture_default_str();
  app.add_option("--min-per-triangle", po.min_per_triangle, "at least this many per triangle")
      ->capture_default_str();
  app.add_flag("--corners", po.corners,
               "points at every triangle's corners (moved inside by a thousandth) instead of "
               "--points: rad's values at its own vertices");
  app.add_option("--seed", po.seed, "seed of the points and of the paths")->capture_default_str();
  app.add_option("--target", to.target_stderr,
                 "standard error per point, as a fraction of the channel's mean radiosity")
      ->capture_default_str();
  app.add_option("--pilot", to.pilot_samples, "samples per point before the target is set")
      ->capture_default_str();
  app.add_option("--max-samples", to.max_samples, "samples per point at most")
      ->capture_default_str();
  app.add_flag("!--no-next-event", to.next_event,
               "count emission only where paths hit emitters (a check on the MIS weights)");
  app.add_option("--max-bounces", to.max_bounces,
                 "bounces after the first surface (0: direct light only; < 0: no limit)")
      ->capture_default_str();
  app.add_option("--threads", threads, "worker threads (0: all cores)")->capture_default_str();
  app.add_option("--reference", reference_path, "reference CSV to compare against");
  app.add_option("--compare", mesh_path, "rad output (.ply) to compare with --reference")
      ->needs("--reference");
  std::string points_path;
  app.add_option("--points-out", points_path, "with --compare: every point's values as CSV")
      ->needs("--compare");
  std::vector<float> ambient;
  app.add_option(
         "--ambient", ambient,
         "with --compare: add reflectance x this ambient radiosity (R G B) to rad's values, "
         "as rad's display does (rad --stats-json gives it as solver.ambient)")
      ->expected(3)
      ->needs("--compare");
  CLI11_PARSE(app, argc, argv);
  if (out_path.empty() == mesh_path.empty()) {
    std::fprintf(stderr,
                 "error: give either -o OUT.csv or --reference REF.csv --compare MESH.ply\n");
    return 2;
  }
  to.seed = po.seed;
  try {
    const rad::Hierarchy h = rad::build_hierarchy(rad::parse_scene_file(scene_path));
    if (threads <= 0) threads = tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    if (!mesh_path.empty()) return compare(h, reference_path, mesh_path, points_path, ambient);
    return generate(h, scene_path, out_path, po, to, threads);
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}
