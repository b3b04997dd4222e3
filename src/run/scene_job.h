// One scene through the whole pipeline: parse, build, solve, write. Used by the single-scene
// command (one process or MPI ranks) and by batch runs.
#pragma once

#include <string>
#include <vector>

#include "run/run_options.h"
#include "solver/ranks.h"
#include "solver/solver.h"

namespace rad {

struct SceneJob {
  SceneInput input;
  OutputOptions outputs;
  std::string stats_json;  // empty: none
  // --checkpoint FILE: the solver state saved every checkpoint_every seconds, when stopped and
  // at the end; a job started with the file present resumes from it.
  std::string checkpoint;
  double checkpoint_every = 60.0;
  size_t max_memory = 0;  // 0: 90% of the machine's (or the cgroup's) memory
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
/// output options and paths, the scene unit (--unit), and rad's version.
uint64_t job_fingerprint(const RunOptions& run, const SceneJob& job, const Hierarchy& h);

/// Runs `job` with the options of `run`, printing the original's stage lines and statistics
/// unless quiet. Every output is checked before solving and written atomically. Throws
/// rad::Error on bad input. With `ranks` (under MPI) every rank runs it together: each
/// receives for its share of the scene, and rank 0 alone speaks and writes the outputs.
SceneJobResult run_scene_job(const RunOptions& run, const SceneJob& job, Ranks* ranks = nullptr);

}  // namespace rad
