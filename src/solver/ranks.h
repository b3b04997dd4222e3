// The processes that solve one scene together under MPI (`mpirun -np N rad ...`): each holds
// the whole geometry for visibility and receives for its own share of the clusters. A run of one
// process has no Ranks at all (Ownership::ranks is null). The one virtual interface is the
// run-time choice between that and MPI; Open MPI's headers stay inside mpi_ranks.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad {

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;

  /// The greatest `value` over the ranks and its `index` (ties: the lowest index), on every rank.
  virtual std::pair<double, int32_t> max_location(double value, int32_t index) = 0;
  /// Element-wise integer sums over the ranks, in place on every rank (exact: in any order).
  virtual void sum(std::span<int64_t> values) = 0;
  /// The greatest value over the ranks, on every rank.
  virtual int64_t max(int64_t value) = 0;
  /// `bytes` of rank `root` on every rank.
  virtual void broadcast(std::string& bytes, int root) = 0;
  /// Rank 0 is handed every rank's `bytes` in rank order (its own first), one at a time, so it
  /// can decode and free each before the next arrives; the others only send.
  virtual void gather(std::string bytes, const std::function<void(int, std::string&)>& take) = 0;
  /// Ends every rank's process with `code` (an error on one rank must not leave the others
  /// waiting in a collective).
  [[noreturn]] virtual void abort(int code) = 0;

  /// Seconds spent inside the calls above (waiting for the slowest rank included), and the
  /// bytes this rank sent through broadcast() as root.
  double communication_seconds = 0.0;
  uint64_t broadcast_bytes = 0;
  uint64_t broadcasts = 0;
};

/// Joins the MPI job this process was started in by mpirun (or srun), or returns null when it
/// was started on its own. Throws rad::Error when started by mpirun in a build without MPI.
/// Call once, first thing in main; the returned object finalises MPI when destroyed.
std::unique_ptr<Ranks> join_ranks(int* argc, char*** argv);

/// The number of processes of this job on this machine (1 when not under MPI): the default
/// thread count shares the cores among them.
int local_rank_count();

}  // namespace rad
