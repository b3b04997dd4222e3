#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>

#include "core/error.h"
#include "solver/ranks.h"

#if RAD_HAVE_MPI
#include <mpi.h>
#endif

namespace rad {

namespace {

// The world size the launcher gave this process, or 0 when no MPI launcher started it.
int launched_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  }
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

}  // namespace

int local_rank_count() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"}) {
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  }
  return 1;
}

#if RAD_HAVE_MPI

namespace {

using Clock = std::chrono::steady_clock;

// Messages are cut into pieces whose size fits MPI's int counts.
constexpr size_t kPiece = size_t(1) << 30;

class MpiRanks final : public Ranks {
 public:
  MpiRanks(int* argc, char*** argv) {
    int provided = 0;
    // Only the main thread calls MPI; TBB's workers never do.
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (provided < MPI_THREAD_FUNNELED) {
      MPI_Finalize();
      throw Error("this MPI library cannot run rad's threads beside it (MPI_THREAD_FUNNELED)");
    }
  }
  ~MpiRanks() override { MPI_Finalize(); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::pair<double, int32_t> max_location(double value, int32_t index) override {
    const Timer t(*this);
    struct {
      double value;
      int index;
    } in{value, index}, out{};
    MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, MPI_COMM_WORLD);
    return {out.value, out.index};
  }

  void sum(std::span<int64_t> values) override {
    const Timer t(*this);
    MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_SUM,
                  MPI_COMM_WORLD);
  }

  int64_t max(int64_t value) override {
    const Timer t(*this);
    int64_t out = 0;
    MPI_Allreduce(&value, &out, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
    return out;
  }

  void broadcast(std::string& bytes, int root) override {
    const Timer t(*this);
    uint64_t n = bytes.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
    if (rank_ == root) {
      broadcast_bytes += n;
      ++broadcasts;
    } else {
      bytes.resize(size_t(n));
    }
    for (size_t at = 0; at < n; at += kPiece) {
      MPI_Bcast(bytes.data() + at, int(std::min(kPiece, size_t(n) - at)), MPI_BYTE, root,
                MPI_COMM_WORLD);
    }
  }

  void gather(std::string bytes, const std::function<void(int, std::string&)>& take) override {
    const Timer t(*this);
    if (rank_ != 0) {
      const uint64_t n = bytes.size();
      MPI_Send(&n, 1, MPI_UINT64_T, 0, 0, MPI_COMM_WORLD);
      for (size_t at = 0; at < n; at += kPiece) {
        MPI_Send(bytes.data() + at, int(std::min(kPiece, size_t(n) - at)), MPI_BYTE, 0, 1,
                 MPI_COMM_WORLD);
      }
      return;
    }
    take(0, bytes);
    std::string().swap(bytes);
    for (int r = 1; r < size_; ++r) {
      uint64_t n = 0;
      MPI_Recv(&n, 1, MPI_UINT64_T, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::string b(size_t(n), '\0');
      for (size_t at = 0; at < n; at += kPiece) {
        MPI_Recv(b.data() + at, int(std::min(kPiece, size_t(n) - at)), MPI_BYTE, r, 1,
                 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
      take(r, b);
    }
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);  // MPI_Abort does not return; in case it does
  }

 private:
  // Adds the lifetime of a call to communication_seconds.
  struct Timer {
    explicit Timer(Ranks& r) : ranks(r) {}
    ~Timer() {
      ranks.communication_seconds += std::chrono::duration<double>(Clock::now() - start).count();
    }
    Ranks& ranks;
    Clock::time_point start = Clock::now();
  };
  int rank_ = 0, size_ = 1;
};

}  // namespace

std::unique_ptr<Ranks> join_ranks(int* argc, char*** argv) {
  if (launched_size() == 0) return nullptr;
  return std::make_unique<MpiRanks>(argc, argv);
}

#else

std::unique_ptr<Ranks> join_ranks(int*, char***) {
  if (launched_size() > 1) {
    throw Error(
        "this rad was built without Open MPI, so it cannot solve one scene across ranks; install "
        "libopenmpi-dev and build again (tools/run does), or run it without mpirun");
  }
  return nullptr;
}

#endif

}  // namespace rad
