// One scene through the whole pipeline: parse, build, solve, write. Used by the single-scene
// command and by batch runs.
#pragma once

#include <string>
#include <vector>

#include "app/cli.h"
#include "solver/ranks.h"
#include "solver/solver.h"

namespace rad {

struct SceneJob {
  std::string scene;
  std::string mesh_output;          // empty: no mesh file
  std::vector<std::string> images;  // rendered with the command line's camera and size
  std::string stats_json;           // empty: none
  // rad batch: when the stats file carries this job's fingerprint (written last, after every
  // other output) and every output exists, the scene is not solved again.
  bool skip_if_done = false;
};

struct SceneJobResult {
  StopReason stop = StopReason::Converged;
  int64_t shots = 0;
  size_t vertices = 0;
  double unshot_fraction = 0.0;
  double seconds = 0.0;
  bool skipped = false;  // skip_if_done found the outputs complete
};

/// What a job's outputs depend on: the solve's fingerprint (scene geometry, hierarchy,
/// materials, flags, every option that changes the answer, backend), the stop criteria, the
/// output options and paths, and rad's version.
uint64_t job_fingerprint(const CommandLine& cmd, const SceneJob& job, const Hierarchy& h);

/// Runs `job` with the options of `cmd`, printing the original's stage lines and statistics
/// unless quiet. Every output is checked before solving and written atomically. Throws
/// rad::Error on bad input. With `ranks` (under MPI) every rank runs it together: each
/// receives for its share of the scene, and rank 0 alone speaks and writes the outputs.
SceneJobResult run_scene_job(const CommandLine& cmd, const SceneJob& job, Ranks* ranks = nullptr);

}  // namespace rad
