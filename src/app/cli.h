// The command line: one option set per mode, built on the run layer's shared sets, and its
// parsing. A mode registers only the options it uses, so any other is a usage error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "run/run_options.h"
#include "run/scene_job.h"
#include "serve/server.h"

namespace rad {

enum class Mode : uint8_t {
  Solve,       // rad [options] SCENE OUTPUT: one scene (or its ranks under mpirun)
  Check,       // rad --check SCENE: parse, validate, summarise
  CrossCheck,  // rad --cross-check B SCENE: two backends compared
  Batch,       // rad batch OUTDIR SCENE...
  Serve,       // rad serve SCENE
  Convert,     // rad convert IN OUT
};

/// rad batch OUTDIR SCENE...: every scene solved with the same options.
struct BatchOptions {
  std::string dir;
  std::vector<std::string> scenes;                 // scene files, or .txt lists of them
  std::vector<std::string> formats{"ply", "png"};  // one output per extension
  int shard_index = 0, shard_count = 1;  // --shard I/N: the scenes i of the list with i % N == I
};

struct CommandLine {
  Mode mode = Mode::Solve;
  RunOptions run;  // every mode that solves
  // The scene and what is written from it. Solve: all of it; Check, CrossCheck: the scene;
  // Batch: the template of every scene's job (outputs named per scene); Serve: the scene and
  // the outputs written when it stops; Convert: the scene (IN).
  SceneJob job;
  std::optional<BackendKind> cross_check;  // CrossCheck: the second backend
  BatchOptions batch;                      // Batch
  ServerOptions server;                    // Serve
  std::string converted;                   // Convert: OUT
};

/// `--shard` of rad batch: "I/N" (0 <= I < N), or "slurm" for the Slurm job array's task index
/// and count. Throws rad::Error otherwise.
void parse_shard(const std::string& text, int* index, int* count);

/// Parses argv. Accepts the original's single-dash flags (-noshadows, -minsize F). Returns
/// nothing when the program should exit with `exit_code` (after --help or a usage error, which
/// it prints).
std::optional<CommandLine> parse_command_line(int argc, char** argv, int* exit_code);

}  // namespace rad
