#include "run/prepared_solve.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <thread>

#include "core/memory.h"
#include "solver/ranks.h"

namespace rad {

int thread_count(int requested) {
  if (requested > 0) return requested;
  // A process bound to some cores (mpirun binds each rank) uses those; an unbound one shares
  // the machine with the other ranks on it.
  const int cores = tbb::info::default_concurrency();
  if (cores < int(std::thread::hardware_concurrency())) return cores;
  return std::max(1, cores / local_rank_count());
}

size_t solve_memory_limit(size_t max_memory, bool under_mpi) {
  if (max_memory > 0) return max_memory;
  return size_t(0.9 * double(machine_memory_bytes()) / double(under_mpi ? local_rank_count() : 1));
}

void limit_kept_answers(SolverOptions& o, size_t memory_limit) {
  if (memory_limit > 0) o.kept_rays_bytes = std::min(o.kept_rays_bytes, memory_limit / 8);
}

// Constructed in place: a global_control copied or moved is not registered with TBB, and the
// original's destructor would lift the limit.
struct PreparedSolve::ThreadLimit {
  explicit ThreadLimit(size_t threads)
      : control(tbb::global_control::max_allowed_parallelism, threads) {}
  tbb::global_control control;
};

PreparedSolve::PreparedSolve(const Hierarchy& h, const RunOptions& o)
    : threads_(thread_count(o.threads)),
      limit_(std::make_unique<ThreadLimit>(size_t(threads_))),
      visibility_(make_visibility_backend(o.backend, h, VisibilityOptions{o.packets})) {}

PreparedSolve::~PreparedSolve() = default;

}  // namespace rad
