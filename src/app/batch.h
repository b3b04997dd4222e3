// rad batch: many scenes with the same options, a summary, and no half-written outputs.
#pragma once

#include "app/cli.h"

namespace rad {

/// Solves every scene of cmd.batch_scenes (expanding .txt lists), writing OUTDIR/<name>.<ext>
/// for each format and OUTDIR/<name>.json, going on when a scene fails (its error printed
/// with file and line). Prints a summary table; returns 0 if all succeeded, 1 otherwise.
int run_batch(const CommandLine& cmd);

}  // namespace rad
