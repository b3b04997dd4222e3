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
//
// The reference seen through a camera (each pixel the mean radiosity over its area, and the
// mask of interior pixels next to it as REF.mask.pgm), and a picture of rad's against it:
//   build/tools/rad-reference scenes/cornell_box.des --camera 278,273,-800,278,273,0
//       --size 200x200 --image-out out/cornell_ref.pfm
//   build/rad scenes/cornell_box.des out/c.ply --camera 278,273,-800,278,273,0 --size 200x200
//       --image out/c.pfm
//   build/tools/rad-reference --compare-image out/c.pfm --reference-image out/cornell_ref.pfm
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "export/camera.h"
#include "hierarchy/hierarchy.h"
#include "reference/buried_points.h"
#include "reference/camera_reference.h"
#include "reference/compare.h"
#include "reference/image_compare.h"
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
      if (!mesh.irradiance.empty()) mesh.irradiance[v] += amb;
    }
  }
  // Textured points: the texel's reflectance and emission at the point, over the irradiance
  // interpolated from rad's vertices.
  std::vector<TexelSurface> texels(ref.points.size());
  size_t textured = 0;
  for (size_t i = 0; i < ref.points.size(); ++i) {
    const size_t p = size_t(ref.points[i].triangle);
    if (p >= h.triangles.size()) continue;
    texels[i] = surface_at(h, p, ref.points[i].position);
    textured += texels[i].textured ? 1 : 0;
  }
  if (textured > 0 && mesh.irradiance.empty()) {
    std::fprintf(stderr,
                 "warning: %s has no irradiance_r/g/b: its %zu textured points are compared by "
                 "their vertices' radiosity, the texture filtered over each element\n",
                 mesh_path.c_str(), textured);
  }
  const RayScene scene(h);
  const std::vector<uint8_t> buried =
      buried_points(scene, h.triangles, ref.points, 1e-5f * h.bounds.diagonal());
  const ComparisonReport r =
      compare_to_reference({mesh.position, mesh.radiosity, mesh.indices, polygon, mesh.irradiance},
                           ref, emitting_polygons(h), buried, texels);
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

// REF.pfm -> REF.mask.pgm: where the mask of a reference image is unless given.
std::string mask_path_for(const std::string& image_path) {
  const size_t dot = image_path.rfind('.');
  const size_t slash = image_path.find_last_of("/\\");
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? image_path.substr(0, dot) : image_path) + ".mask.pgm";
}

void parse_size(const std::string& text, int& width, int& height) {
  const size_t x = text.find('x');
  char* end = nullptr;
  const std::string w = text.substr(0, x), h = x == std::string::npos ? "" : text.substr(x + 1);
  width = int(std::strtol(w.c_str(), &end, 10));
  const bool w_ok = !w.empty() && !*end;
  height = int(std::strtol(h.c_str(), &end, 10));
  if (!w_ok || h.empty() || *end || width < 1 || height < 1 || width > 16384 || height > 16384) {
    throw rad::Error("--size takes WxH, e.g. 200x200, not '" + text + "'");
  }
}

int camera_reference(const rad::Hierarchy& h, const std::string& scene_path,
                     const std::string& camera_text, const std::string& size_text,
                     const std::string& out_path, std::string mask_path,
                     rad::CameraReferenceOptions o, int threads) {
  using namespace rad;
  o.camera = parse_camera(camera_text);
  parse_size(size_text, o.width, o.height);
  if (mask_path.empty()) mask_path = mask_path_for(out_path);
  std::fprintf(stderr, "%dx%d pixels, %d x %d paths each, %d threads\n", o.width, o.height,
               o.pixel_samples, o.pixel_samples, threads);
  int last = -1;
  const CameraReference ref = render_camera_reference(h, o, [&](int done, int total) {
    if (done * 20 / total != last * 20 / total || done == total) {
      std::fprintf(stderr, "\r%d / %d rows", done, total);
      std::fflush(stderr);
    }
    last = done;
  });
  std::fputc('\n', stderr);
  FloatImage img{ref.width, ref.height, ref.radiosity};
  write_pfm(out_path, img);
  write_mask_pgm(mask_path, ref.interior, ref.width, ref.height);
  size_t interior = 0;
  for (uint8_t m : ref.interior) interior += m;
  std::fprintf(stderr, "%s: %s, camera %s; %llu paths in %.0f s; %zu of %zu pixels interior (%s)\n",
               out_path.c_str(), scene_path.c_str(), camera_spec(o.camera).c_str(),
               static_cast<unsigned long long>(ref.paths), ref.seconds, interior,
               ref.interior.size(), mask_path.c_str());
  return 0;
}

int compare_image(const std::string& image_path, const std::string& reference_path,
                  std::string mask_path) {
  using namespace rad;
  const FloatImage image = read_pfm(image_path);
  const FloatImage reference = read_pfm(reference_path);
  if (mask_path.empty()) mask_path = mask_path_for(reference_path);
  const std::vector<uint8_t> mask = read_mask_pgm(mask_path, reference.width, reference.height);
  std::fputs(format_image_comparison(compare_images(image, reference, mask)).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Path-traced radiosity reference for a rad scene, and comparison against it."};
  std::string scene_path, out_path, reference_path, mesh_path;
  rad::PointOptions po;
  rad::TraceOptions to;
  int threads = 0;
  app.add_option("SCENE", scene_path, "scene description (.des)");
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
  std::string camera_text, size_text = "200x200", image_out, mask_path, compare_image_path,
                           reference_image;
  rad::CameraReferenceOptions co;
  app.add_option("--camera", camera_text,
                 "the reference through a camera: ex,ey,ez,tx,ty,tz[,fov_deg] (up +y, as rad's "
                 "--camera), written with --image-out");
  app.add_option("--size", size_text, "with --camera: image size WxH in pixels")
      ->capture_default_str();
  app.add_option("--pixel-samples", co.pixel_samples,
                 "with --camera: paths per pixel along each side (k: k x k per pixel, one per "
                 "stratum of its area)")
      ->capture_default_str();
  app.add_option("--image-out", image_out,
                 "with --camera: the reference image to write (.pfm, linear radiosity)")
      ->needs("--camera");
  app.add_option("--mask", mask_path,
                 "the interior mask (binary PGM) written with --image-out or read with "
                 "--compare-image (default: the reference image's name, .mask.pgm)");
  app.add_option("--reference-image", reference_image, "reference image (.pfm) of --camera");
  app.add_option("--compare-image", compare_image_path,
                 "rad's picture (.pfm) to compare with --reference-image: its mean relative "
                 "error over the interior pixels and over all of them")
      ->needs("--reference-image");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!compare_image_path.empty())
      return compare_image(compare_image_path, reference_image, mask_path);
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  const int modes = !out_path.empty() + !mesh_path.empty() + !image_out.empty();
  if (modes != 1 || scene_path.empty()) {
    std::fprintf(stderr,
                 "error: give SCENE and one of -o OUT.csv, --reference REF.csv --compare "
                 "MESH.ply, --camera SPEC --image-out REF.pfm; or --compare-image IMAGE.pfm "
                 "--reference-image REF.pfm\n");
    return 2;
  }
  to.seed = po.seed;
  try {
    const rad::Hierarchy h = rad::build_hierarchy(rad::parse_scene_file(scene_path));
    if (threads <= 0) threads = tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    if (!mesh_path.empty()) return compare(h, reference_path, mesh_path, points_path, ambient);
    if (!image_out.empty()) {
      co.trace = to;
      return camera_reference(h, scene_path, camera_text, size_text, image_out, mask_path, co,
                              threads);
    }
    return generate(h, scene_path, out_path, po, to, threads);
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}
