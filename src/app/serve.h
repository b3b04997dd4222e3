// `rad serve` from start to stop: parse, build, solve in the background while serving the page,
// and on Ctrl-C or SIGTERM write the requested files from where the solve got to.
#pragma once

#include "app/cli.h"

namespace rad {

/// Runs the server until SIGINT or SIGTERM, prints its address first. Output names are checked
/// and the page's modules located before anything is solved. Returns the exit status; throws
/// rad::Error on bad input (scene, output names, missing modules, an address it cannot bind).
int run_serve(const CommandLine& cmd);

}  // namespace rad
