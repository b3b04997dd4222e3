// The command line: one option set per mode, built on the run layer's shared sets, and its
// parsing. A mode registers only the options it uses, so any other is a usage error.
#pragma once

#include <optional>
#include <string>
#include <string_view>
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

/// rad's exit statuses, listed in every mode's --help. A run stopped by SIGINT or SIGTERM
/// exits with 128 + the signal (interrupted_exit_status, core/interrupt.h).
constexpr int kExitDone = 0;
constexpr int kExitInputError = 1;  // a scene or file that cannot be read or written
constexpr int kExitUsage = 2;       // the command line itself: an unknown option, a bad value

/// Edits (a letter dropped, added, changed, or two neighbours swapped) that turn a into b.
size_t edit_distance(std::string_view a, std::string_view b);

/// The name in `names` nearest to `typed`, if it is close enough to be what was meant (about an
/// edit in three letters, dashes not counted).
std::optional<std::string> nearest_option(const std::string& typed,
                                          const std::vector<std::string>& names);

/// `page`, rad's man page, with the option entries between its lines `.\" BEGIN OPTIONS` and
/// `.\" END OPTIONS` made from the definitions --help prints: rad's options group by group, each
/// with its names, its value and its description, then what each other mode takes. So the page
/// and the help say the same (tools/man_options.cpp writes it; ManPage.OptionsAreTheHelps checks
/// it). Throws rad::Error when the page has no such lines.
std::string man_page_with_options(const std::string& page);

/// Parses argv. Accepts the original's single-dash flags (-noshadows, -minsize F). Returns
/// nothing when the program should exit with `exit_code`: kExitDone after --help or --version,
/// kExitUsage after a usage error, which it prints naming the argument and how to mend it.
std::optional<CommandLine> parse_command_line(int argc, char** argv, int* exit_code);

}  // namespace rad
