// A scene made ready to solve (after load_hierarchy read it): the start of every mode that
// solves.
#pragma once

#include <memory>

#include "hierarchy/hierarchy.h"
#include "run/run_options.h"
#include "visibility/backend.h"

namespace rad {

/// Worker threads of one process: `requested`, or the cores shared among the MPI ranks that run
/// on this machine (all of them without MPI).
int thread_count(int requested);

/// The memory a solve may take: `max_memory` when given (> 0), else 90% of this machine's (or
/// its cgroup's), shared by the MPI ranks that run on it (`under_mpi`).
size_t solve_memory_limit(size_t max_memory, bool under_mpi);

/// Kept shadow-ray answers (solver/kept_rays.h) take at most an eighth of a solve's memory.
void limit_kept_answers(SolverOptions& o, size_t memory_limit);

/// The visibility backend over a hierarchy, and TBB held at the run's thread count for as long
/// as this lives (the backend's build included).
class PreparedSolve {
 public:
  PreparedSolve(const Hierarchy& h, const RunOptions& o);
  ~PreparedSolve();
  PreparedSolve(const PreparedSolve&) = delete;
  PreparedSolve& operator=(const PreparedSolve&) = delete;

  int threads() const { return threads_; }
  const VisibilityBackend& visibility() const { return *visibility_; }

 private:
  struct ThreadLimit;  // TBB's global control, kept out of this header
  int threads_;
  std::unique_ptr<ThreadLimit> limit_;
  std::unique_ptr<VisibilityBackend> visibility_;
};

}  // namespace rad
