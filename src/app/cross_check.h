// rad --cross-check: one scene through two visibility backends, every disagreement reported.
#pragma once

#include "app/cli.h"

namespace rad {

/// Compares cmd.backend with *cmd.cross_check on cmd.scene: both backends' answers to random
/// shadow segments against brute force (each mismatch printed with its segment), then the two
/// solves with cmd.solver (same vertices, radiosity within 1e-5 of the largest). Prints a report
/// on stdout; returns 0 when they agree, 1 when not. Throws rad::Error on bad input.
int run_cross_check(const CommandLine& cmd);

}  // namespace rad
