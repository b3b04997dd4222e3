// rad batch: many scenes with the same options, a summary, and no half-written outputs.
#pragma once

#include "app/cli.h"

namespace rad {

/// Solves every scene of cmd.batch_scenes (expanding .txt lists) in this process's shard
/// (--shard I/N: scenes I, I + N, ...), writing OUTDIR/<name>.<ext> for each format and
/// OUTDIR/<name>.json, going on when a scene fails (its error printed with file and line). A
/// scene whose outputs an earlier run completed with the same fingerprint is skipped. Each
/// scene's row is merged into OUTDIR/batch.json. Prints a table; returns 0 if all succeeded.
int run_batch(const CommandLine& cmd);

}  // namespace rad
