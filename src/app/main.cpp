// rad: scene text -> parse -> hierarchy -> mesh -> visibility -> solver -> export.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

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
#include "solver/ranks.h"

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

int run(const rad::CommandLine& cmd, rad::Ranks* ranks) {
  using namespace rad;
  if (ranks && ranks->size() > 1 &&
      (cmd.convert || cmd.batch || cmd.serve || cmd.cross_check || cmd.check)) {
    throw Error(
        "under mpirun rad solves one scene (rad [options] SCENE OUTPUT); rad batch spreads "
        "scenes over machines with --shard instead");
  }
  if (cmd.convert) return run_convert(cmd);
  if (cmd.batch) return run_batch(cmd);
  if (cmd.serve) return run_serve(serve_config(cmd));
  if (cmd.cross_check) return run_cross_check(cmd);
  if (cmd.check) {
    std::fputs(summarize(load_hierarchy(cmd.scene, cmd.model, cmd.hierarchy)).c_str(), stdout);
    return 0;
  }
  run_scene_job(cmd, SceneJob{cmd.scene, cmd.output, cmd.images, cmd.stats_json}, ranks);
  // Stopped by Ctrl-C or SIGTERM: the outputs hold the solution so far; say so in the status.
  return interrupt_signal() ? interrupted_exit_status(interrupt_signal()) : 0;
}

// Prints an error once. Under MPI it names the rank and ends every rank: the others may be
// waiting for this one in a collective. An error that every rank meets (a bad scene) is printed
// by rank 0, which the others give a second to end the job first.
void fail(const std::string& message, rad::Ranks* ranks) {
  if (!ranks || ranks->size() == 1) {
    std::fprintf(stderr, "%s\n", message.c_str());
    return;
  }
  if (ranks->rank() != 0) std::this_thread::sleep_for(std::chrono::seconds(1));
  std::fprintf(stderr, "rad rank %d of %d: %s\n", ranks->rank(), ranks->size(), message.c_str());
  std::fflush(stderr);
  ranks->abort(1);
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<rad::Ranks> ranks;
  try {
    ranks = rad::join_ranks(&argc, &argv);
    int code = 0;
    const auto cmd = rad::parse_command_line(argc, argv, &code);
    if (!cmd) return code;
    return run(*cmd, ranks.get());
  } catch (const rad::Error& e) {
    fail(e.what(), ranks.get());
  } catch (const std::exception& e) {
    fail(std::string("error: ") + e.what(), ranks.get());
  }
  return 1;
}
