// rad: scene text -> parse -> hierarchy -> mesh -> visibility -> solver -> export.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <memory>

#include "app/cli.h"
#include "app/report.h"
#include "core/error.h"
#include "core/progress.h"
#include "export/exposure.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"
#include "export/output_mesh.h"
#include "hierarchy/hierarchy.h"
#include "scene/parser.h"
#include "serve/run_serve.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

rad::ServeConfig serve_config(const rad::CommandLine& cmd) {
  rad::ServeConfig c;
  c.scene = cmd.scene;
  c.server.host = cmd.host;
  c.server.port = cmd.port;
  c.session.solver = cmd.solver;
  c.session.ambient = cmd.ambient;
  c.session.curve = cmd.tonemap;
  c.session.exposure = cmd.exposure;
  c.backend = cmd.backend;
  c.packets = cmd.packets;
  c.threads = cmd.threads;
  c.output = cmd.output;
  c.images = cmd.images;
  c.camera = cmd.camera;
  c.image_width = cmd.image_width;
  c.image_height = cmd.image_height;
  c.ascii = cmd.ascii;
  c.quiet = cmd.quiet;
  return c;
}

int run(const rad::CommandLine& cmd) {
  using namespace rad;
  if (cmd.serve) return run_serve(serve_config(cmd));
  const auto start = Clock::now();
  Progress progress(cmd.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
  // Stages go to stdout as the original printed them; the progress bar lives on stderr.
  auto say = [&](const std::string& s) {
    if (cmd.quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  RunTimes times;
  if (!cmd.check) check_mesh_extension(cmd.output);
  for (const std::string& image : cmd.images) check_image_extension(image);

  if (!cmd.check) say("Reading description file...");
  const SceneDescription scene = parse_scene_file(cmd.scene);
  const Hierarchy hierarchy = build_hierarchy(scene);
  times.parse = since(start);
  if (cmd.check) {
    std::fputs(summarize(hierarchy).c_str(), stdout);
    return 0;
  }

  say("Initializing...");
  const int threads = cmd.threads > 0 ? cmd.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  auto t = Clock::now();
  const std::unique_ptr<VisibilityBackend> visibility =
      make_visibility_backend(cmd.backend, hierarchy, VisibilityOptions{cmd.packets});
  SolverState state = make_solver_state(hierarchy, cmd.solver);
  times.build = since(t);

  say(fmt::format("Starting Computation ({} triangles, {} backend, {} thread{})",
                  hierarchy.triangles.size(), to_string(cmd.backend), threads,
                  threads == 1 ? "" : "s"));
  t = Clock::now();
  const double log_goal = std::log(std::max(cmd.solver.converge, 1e-12));
  const StopReason stop = solve(state, *visibility, [&](const SolverState& s, const ShotRecord& r) {
    const double f = r.unshot_fraction > 0 ? std::log(r.unshot_fraction) / log_goal : 1.0;
    progress.update(f, fmt::format("shot {}  unshot {:.2e}  elements {}", r.shot,
                                   r.unshot_fraction, s.stats.subdivisions * 3 + s.mesh.polygons.size()));
  });
  times.solve = since(t);
  progress.finish(fmt::format("{} after {} shots", to_string(stop), state.shots));

  say(fmt::format("Writing results in file {}", cmd.output));
  t = Clock::now();
  const OutputMesh mesh = make_output_mesh(state, cmd.ambient);
  MeshFileOptions mo;
  mo.ascii = cmd.ascii;
  mo.tone = scene_tone_map(state, mesh, cmd.tonemap, cmd.exposure);
  write_mesh_file(cmd.output, mesh, mo);
  if (!cmd.images.empty()) {
    const RenderOptions ro{cmd.image_width, cmd.image_height};
    const Camera camera = cmd.camera ? *cmd.camera
                                     : default_camera(mesh.position, mesh.indices,
                                                      float(ro.width) / float(ro.height));
    const Image image = render_image(mesh.position, mesh.display, mesh.indices, camera, ro);
    for (const std::string& path : cmd.images) {
      say(fmt::format("Writing image {}", path));
      write_image_file(path, image, mo.tone);
    }
  }
  times.write = since(t);
  times.total = since(start);
  if (!cmd.stats_json.empty()) write_stats_json(cmd.stats_json, cmd, state, stop, times);
  if (!cmd.quiet) std::fputs(format_statistics(state, times.total).c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int code = 0;
    const auto cmd = rad::parse_command_line(argc, argv, &code);
    if (!cmd) return code;
    return run(*cmd);
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
  return 1;
}
