// A prepared solve holds the run's thread count for as long as it lives, and the backend asked.
#include "run/prepared_solve.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <thread>

#include "../solver/scene_builder.h"

namespace rad {
namespace {

size_t allowed_threads() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

TEST(PreparedSolve, HoldsTheThreadCountWhileItLivesAndBuildsTheBackendAsked) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(1.0f), Vec3(0.5f), Vec3(0.0f));
  const Hierarchy h = build_hierarchy(d);
  for (BackendKind kind : {BackendKind::Embree, BackendKind::Grid, BackendKind::Brute}) {
    RunOptions o;
    o.backend = kind;
    o.threads = 1;
    {
      const PreparedSolve p(h, o);
      EXPECT_EQ(p.threads(), 1);
      EXPECT_EQ(allowed_threads(), 1u);
      EXPECT_EQ(p.visibility().kind(), kind);
    }
    // Released: back to TBB's default for the machine.
    EXPECT_EQ(allowed_threads(), size_t(tbb::info::default_concurrency()));
  }
}

TEST(PreparedSolve, ThreadCountIsTheRequestOrEveryCoreWithoutMpi) {
  EXPECT_EQ(thread_count(3), 3);
  EXPECT_GE(thread_count(0), 1);
  EXPECT_LE(thread_count(0), int(std::max(1u, std::thread::hardware_concurrency())));
}

}  // namespace
}  // namespace rad
