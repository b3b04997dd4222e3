// The shots of a solve so far: what each shot, for gathering again, and the history.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/shot_source.h"

namespace rad {

/// One line of the convergence history.
struct ShotRecord {
  int64_t shot;            // 1-based
  int32_t source;          // cluster that shot, or -1 - i for light i (Hierarchy::lights)
  double seconds;          // since the solve began
  double unshot_fraction;  // unshot / emitted energy after the shot
};

struct ShotLog {
  /// The shots new vertices gather again, in order: every one, or the major ones only without
  /// SolverOptions::log_minor_shots. Refinement's midpoints gather the major ones again;
  /// vertices made by a forced subdivision gather all of these, so their radiosity is exact.
  std::vector<ShotSource> sources;
  int64_t count = 0;  // shots taken so far
  std::vector<ShotRecord> history;
  /// What a shot of each cluster costs, in vertices gathered (those of its last shot's
  /// receivers; 0: not shot yet), for choosing the shooter (solver.cpp).
  std::vector<double> cluster_cost;
};

}  // namespace rad
