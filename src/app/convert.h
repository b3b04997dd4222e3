// rad convert IN OUT: bring a model in once, edit it as a description, take it back out.
#pragma once

#include "app/cli.h"

namespace rad {

/// Reads cmd.scene (a description or a model), builds its hierarchy and writes it to cmd.output
/// in the format the extension names (export/scene_export.h), saying once on stdout what the
/// target format could not hold. Throws rad::Error (before anything is written for a bad
/// output name or a bad input). Returns the exit status.
int run_convert(const CommandLine& cmd);

}  // namespace rad
