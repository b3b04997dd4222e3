// Set-up costs per scene and size (Google Benchmark): the object hierarchy, the Embree BVH, the
// voxel grids and the solver's initial state, each on 1 and on all cores.
//
//   build_bench [--benchmark_filter=...] [--benchmark_out=build.json]
//   RAD_BENCH_TRIANGLES=50000   size of the generated scenes (default 50000; also a tenth of it)
//   RAD_BENCH_LARGE=1           also the 1M-triangle building
//
// Names read kind/scene/backend/-/threads, e.g. build/building_50000/embree/-/t2.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scenegen/scenegen.h"
#include "solver/solver_state.h"
#include "visibility/backend.h"

namespace rad {
namespace {

struct Scene {
  SceneDescription description;
  Hierarchy hierarchy;
};

const Scene& scene(SceneKind kind, uint64_t triangles) {
  static std::map<std::pair<SceneKind, uint64_t>, std::unique_ptr<Scene>> cache;
  auto& slot = cache[{kind, triangles}];
  if (!slot) {
    slot = std::make_unique<Scene>();
    slot->description = generate_scene(kind, triangles, 1);
    slot->hierarchy = build_hierarchy(slot->description);
  }
  return *slot;
}

enum class What { Hierarchy, Embree, Grid, SolverState };
const char* to_string(What w) {
  switch (w) {
    case What::Hierarchy:
      return "hierarchy";
    case What::Embree:
      return "embree";
    case What::Grid:
      return "grid";
    case What::SolverState:
      return "solver-state";
  }
  return "?";
}

void bm_build(benchmark::State& st, SceneKind kind, uint64_t tris, What what, int threads) {
  const Scene& s = scene(kind, tris);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  for (auto _ : st) {
    switch (what) {
      case What::Hierarchy:
        benchmark::DoNotOptimize(build_hierarchy(s.description));
        break;
      case What::Embree:
        benchmark::DoNotOptimize(make_visibility_backend(BackendKind::Embree, s.hierarchy));
        break;
      case What::Grid:
        benchmark::DoNotOptimize(make_visibility_backend(BackendKind::Grid, s.hierarchy));
        break;
      case What::SolverState:
        benchmark::DoNotOptimize(make_solver_state(s.hierarchy, SolverOptions{}));
        break;
    }
  }
  st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(s.hierarchy.triangles.size()));
  st.counters["triangles"] = double(s.hierarchy.triangles.size());
  st.counters["objects"] = double(s.hierarchy.objects.size());
  st.counters["threads"] = threads;
}

void register_all() {
  const char* size = std::getenv("RAD_BENCH_TRIANGLES");
  const char* large = std::getenv("RAD_BENCH_LARGE");
  const uint64_t n = size && *size ? std::strtoull(size, nullptr, 10) : 50000;
  const int all = tbb::info::default_concurrency();
  std::vector<std::pair<SceneKind, uint64_t>> scenes;
  for (SceneKind k : {SceneKind::CornellBox, SceneKind::Soup, SceneKind::Nested,
                      SceneKind::TeapotInStadium, SceneKind::Building}) {
    for (uint64_t tris : {n / 10, n}) scenes.push_back({k, tris});
  }
  if (large && std::string(large) == "1") scenes.push_back({SceneKind::Building, 1000000});
  std::vector<int> thread_counts = {1};
  if (all >= 2) thread_counts.push_back(all);
  for (const auto& [kind, tris] : scenes) {
    for (What w : {What::Hierarchy, What::Embree, What::Grid, What::SolverState}) {
      for (int t : thread_counts) {
        const std::string name = std::string("build/") + to_string(kind) + "_" +
                                 std::to_string(tris) + "/" + to_string(w) + "/-/t" +
                                 std::to_string(t);
        benchmark::RegisterBenchmark(name.c_str(),
                                     [=](benchmark::State& st) { bm_build(st, kind, tris, w, t); })
            ->UseRealTime()
            ->MinTime(0.2)
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
}

}  // namespace
}  // namespace rad

int main(int argc, char** argv) {
  rad::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
