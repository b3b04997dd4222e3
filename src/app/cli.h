// The command line: options, their defaults and their parsing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/camera.h"
#include "export/tonemap.h"
#include "hierarchy/auto_hierarchy.h"
#include "scene/model_scene.h"
#include "solver/options.h"
#include "visibility/backend.h"

namespace rad {

struct CommandLine {
  std::string scene;                       // a description (.des) or a model (.obj, .ply)
  ModelOptions model;                      // --emit rules for a model
  std::optional<HierarchyMode> hierarchy;  // --hierarchy; none: auto for models, file else
  std::string output;                      // empty with --check
  bool check = false;                      // parse, validate, summarise; no solve
  std::optional<BackendKind> cross_check;  // --cross-check B: solve with --backend and B, compare
  BackendKind backend = BackendKind::Embree;
  bool packets = true;
  int threads = 0;  // 0: all cores
  SolverOptions solver;
  bool ascii = false;
  bool ambient = true;
  ToneCurve tonemap = ToneCurve::Clamp;
  float exposure = 0.0f;                      // stops added to the automatic exposure
  std::vector<std::string> images;            // --image, repeatable: .png, .hdr, .exr or .pfm
  std::optional<Camera> camera;               // --camera; none: default_camera frames the scene
  int image_width = 800, image_height = 800;  // --size WxH
  std::string stats_json;
  // --checkpoint FILE: the solver state saved every checkpoint_every seconds, when stopped and
  // at the end; a run started with the file present resumes from it.
  std::string checkpoint;
  double checkpoint_every = 60.0;
  size_t max_memory = 0;  // --max-memory; 0: 90% of the machine's (or the cgroup's) memory
  bool quiet = false;
  // rad batch OUTDIR SCENE...: every scene solved with the same options.
  bool batch = false;
  std::string batch_dir;
  std::vector<std::string> batch_scenes;                 // .des files, or .txt lists of them
  std::vector<std::string> batch_formats{"ply", "png"};  // one output per extension
  int shard_index = 0, shard_count = 1;  // --shard I/N: the scenes i of the list with i % N == I
  // rad convert IN OUT: the scene itself in another format (scene: IN, output: OUT).
  bool convert = false;
  // rad serve SCENE [--port P] [--host H]: the interactive mode (output: --output, optional).
  bool serve = false;
  std::string host = "127.0.0.1";
  int port = 8080;
};

/// `--shard` of rad batch: "I/N" (0 <= I < N), or "slurm" for the Slurm job array's task index
/// and count. Throws rad::Error otherwise.
void parse_shard(const std::string& text, int* index, int* count);

/// Worker threads of one process: --threads, or the cores shared among the MPI ranks that run
/// on this machine (all of them without MPI).
int thread_count(const CommandLine& cmd);

/// Parses argv. Accepts the original's single-dash flags (-noshadows, -minsize F). Returns
/// nothing when the program should exit with `exit_code` (after --help or a usage error, which
/// it prints).
std::optional<CommandLine> parse_command_line(int argc, char** argv, int* exit_code);

}  // namespace rad
