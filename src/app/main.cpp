// rad: scene text -> parse -> hierarchy -> mesh -> visibility -> solver -> export.
#include <cstdio>

#include "app/batch.h"
#include "app/cli.h"
#include "app/convert.h"
#include "app/cross_check.h"
#include "app/scene_job.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "scene/scene_file.h"
#include "serve/run_serve.h"

namespace {

rad::ServeConfig serve_config(const rad::CommandLine& cmd) {
  rad::ServeConfig c;
  c.scene = cmd.scene;
  c.model = cmd.model;
  c.hierarchy = cmd.hierarchy;
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
  if (cmd.convert) return run_convert(cmd);
  if (cmd.batch) return run_batch(cmd);
  if (cmd.serve) return run_serve(serve_config(cmd));
  if (cmd.cross_check) return run_cross_check(cmd);
  if (cmd.check) {
    std::fputs(summarize(load_hierarchy(cmd.scene, cmd.model, cmd.hierarchy)).c_str(), stdout);
    return 0;
  }
  run_scene_job(cmd, SceneJob{cmd.scene, cmd.output, cmd.images, cmd.stats_json});
  // Stopped by Ctrl-C or SIGTERM: the outputs hold the solution so far; say so in the status.
  return interrupt_signal() ? interrupted_exit_status(interrupt_signal()) : 0;
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
