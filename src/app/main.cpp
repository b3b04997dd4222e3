// rad: scene text or model -> parse -> hierarchy -> mesh -> visibility -> solver -> export,
// through the run layer (run/) that every mode shares.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "app/batch.h"
#include "app/cli.h"
#include "app/convert.h"
#include "app/cross_check.h"
#include "app/serve.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "run/scene_checks.h"
#include "run/scene_job.h"
#include "run/scene_unit.h"
#include "scene/scene_file.h"
#include "scene/stage.h"
#include "solver/ranks.h"

namespace {

int run(const rad::CommandLine& cmd, rad::Ranks* ranks) {
  using namespace rad;
  if (ranks && ranks->size() > 1 && cmd.mode != Mode::Solve) {
    throw Error(
        "under mpirun rad solves one scene (rad [options] SCENE OUTPUT); rad batch spreads "
        "scenes over machines with --shard instead");
  }
  switch (cmd.mode) {
    case Mode::Convert:
      return run_convert(cmd);
    case Mode::Batch:
      return run_batch(cmd);
    case Mode::Serve:
      return run_serve(cmd);
    case Mode::CrossCheck:
      return run_cross_check(cmd);
    case Mode::Check: {
      const SceneInput& in = cmd.job.input;
      check_scene_input(in);
      const Hierarchy h = load_scene(in);
      std::fputs(summarize(h).c_str(), stdout);
      if (h.model && h.model->stage)
        std::puts(describe_stage(*h.model->stage, metres_per_unit(in)).c_str());
      return kExitDone;
    }
    case Mode::Solve:
      break;
  }
  run_scene_job(cmd.run, cmd.job, ranks);
  // Stopped by Ctrl-C or SIGTERM: the outputs hold the solution so far; say so in the status.
  return interrupt_signal() ? interrupted_exit_status(interrupt_signal()) : kExitDone;
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
  ranks->abort(rad::kExitInputError);
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<rad::Ranks> ranks;
  try {
    ranks = rad::join_ranks(&argc, &argv);
    int code = rad::kExitDone;
    const auto cmd = rad::parse_command_line(argc, argv, &code);
    if (!cmd) return code;
    rad::show_warnings(!cmd->run.quiet);
    return run(*cmd, ranks.get());
  } catch (const rad::Error& e) {
    fail(e.what(), ranks.get());
  } catch (const std::exception& e) {
    fail(std::string("error: ") + e.what(), ranks.get());
  }
  return rad::kExitInputError;
}
