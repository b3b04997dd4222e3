// What a run prints and saves about itself: the original's statistics block and JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "export/camera.h"
#include "export/seams.h"
#include "run/run_options.h"
#include "run/scene_job.h"
#include "solver/distribute.h"
#include "solver/light_groups.h"
#include "solver/solver.h"

namespace rad {

/// rad's version: CMake's project version.
const char* rad_version();

/// Timings of the phases of one run, in seconds.
struct RunTimes {
  double parse = 0, build = 0, solve = 0, write = 0, total = 0;
  double gather = 0;  // MPI: rank 0 taking the ranks' polygons at the end (with the checkpoint)
  double render = 0;  // images by final gather (within `write`)
};

/// The statistics block as the original printed it, plus rad's own counters.
std::string format_statistics(const SolverState& s, double elapsed_seconds);

/// Writes the JSON statistics (schema "rad-stats", version 1; see README) atomically.
void write_stats_json(const std::string& path, const RunOptions& run, const SceneJob& job,
                      const SolverState& s, StopReason stop, const RunTimes& times,
                      const SeamReport& seams, const std::optional<Camera>& camera = {},
                      uint64_t job_fingerprint = 0, const std::vector<RankReport>& ranks = {});

/// The "job_fingerprint" a stats file was written with (rad batch's record that a scene's
/// outputs are complete), or nothing when the file is missing, unreadable or has none.
std::optional<uint64_t> read_job_fingerprint(const std::string& stats_json);

/// Peak resident memory of this process, bytes (0 if unknown).
size_t peak_memory_bytes();

}  // namespace rad
