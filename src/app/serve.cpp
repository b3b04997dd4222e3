#include "app/serve.h"

#include <fmt/format.h>

#include <csignal>
#include <cstdio>

#include "core/error.h"
#include "hierarchy/auto_hierarchy.h"
#include "run/prepared_solve.h"
#include "run/scene_checks.h"
#include "run/scene_unit.h"
#include "run/write_outputs.h"
#include "serve/session.h"
#include "serve/shutdown.h"
#include "serve/web_assets.h"

namespace rad {

int run_serve(const CommandLine& cmd) {
  const RunOptions& run = cmd.run;
  const OutputOptions& outputs = cmd.job.outputs;
  auto say = [&](const std::string& s) {
    if (run.quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  check_outputs(outputs);
  WebAssets assets = load_web_assets(default_web_modules_dir());

  const SceneInput& in = cmd.job.input;
  check_scene_input(in);  // no light is no error here: the page can give an object some
  const Hierarchy hierarchy = load_scene(in);
  const PreparedSolve prepared(hierarchy, run);
  SessionOptions so;
  so.solver = run.solver;
  limit_kept_answers(so.solver, solve_memory_limit(0, false));
  so.ambient = outputs.ambient;
  so.curve = outputs.tonemap;
  so.exposure = outputs.exposure;
  so.metres_per_unit = metres_per_unit(in);
  Session session(hierarchy, prepared.visibility(), so);
  Server server(session, std::move(assets), cmd.server);
  server.bind();
  if (!is_loopback_host(cmd.server.host)) {
    warn({}, fmt::format("serving on {}: anyone who can reach this address can see and edit "
                         "the scene",
                         cmd.server.host));
  }
  session.start();
  server.start();
  // The address goes out even with --quiet: it is what the user (or a test) needs.
  std::printf("rad serve: %s (%zu triangles, %s backend); Ctrl-C stops%s\n", server.url().c_str(),
              hierarchy.triangles.size(), to_string(run.backend),
              outputs.mesh.empty() ? "" : fmt::format(" and writes {}", outputs.mesh).c_str());
  std::fflush(stdout);

  const int sig = wait_for_shutdown();
  say(fmt::format("\nStopping ({})", sig == SIGTERM ? "SIGTERM" : "Ctrl-C"));
  server.stop();
  session.stop();

  const auto snap = session.snapshot();
  say(fmt::format("{} shots, unshot fraction {:.3e}, {} elements", snap->shots,
                  snap->unshot_fraction, snap->elements));
  StagedFiles files;
  write_outputs(snap->mesh, outputs, snap->tone, say, files);  // the exposure the page showed
  files.commit();
  return 0;
}

}  // namespace rad
