// Shadow-ray throughput (rays/s as items_per_second) of each visibility backend on generated
// scenes, in the solver's pattern: one receiving vertex → 16 samples on a source triangle, one
// occluded() call per vertex.
//
//   visibility_bench [--benchmark_filter=...] [--benchmark_format=json]
//   RAD_BENCH_TRIANGLES=1000000  scene size (default 100000)
//   RAD_BENCH_GRID_SWEEP=1       also time the grid at 1 … 32 cells per triangle
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/denormals.h"
#include "scenegen/scenegen.h"
#include "visibility/backend.h"
#include "visibility/grid_backend.h"

namespace rad {
namespace {

constexpr size_t kSamples = 16;
constexpr size_t kVertices = 8192;

struct BenchScene {
  Hierarchy hierarchy;
  std::vector<Segment> segments;  // kVertices × kSamples, vertex-major
};

// Receiving points are random triangle corners; sources are random emitting triangles (random
// triangles if the scene has no emitter), sampled on a regular 4 × 4 stratification.
std::vector<Segment> vertex_to_source_segments(const Hierarchy& h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<uint32_t> sources;
  for (const SceneObject& o : h.objects) {
    if (o.kind == ObjectKind::Pure && max_component(o.material.emission) > 0.0f) {
      for (uint32_t t = 0; t < o.triangle_count; ++t) sources.push_back(o.first_triangle + t);
    }
  }
  std::uniform_int_distribution<uint32_t> any(0, uint32_t(h.triangles.size()) - 1);
  const float offset = shadow_offset(h.bounds);
  std::vector<Segment> out;
  out.reserve(kVertices * kSamples);
  while (out.size() < kVertices * kSamples) {
    uint32_t r = any(rng);
    uint32_t s = sources.empty() ? any(rng) : sources[rng() % sources.size()];
    if (r == s) continue;
    Vec3 from = h.triangles.corners[r][rng() % 3], n_from = h.triangles.normal[r];
    const auto& src = h.triangles.corners[s];
    Vec3 n_src = h.triangles.normal[s];
    for (size_t k = 0; k < kSamples; ++k) {
      float a = (float(k % 4) + u(rng)) / 4.0f, b = (float(k / 4) + u(rng)) / 4.0f;
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      Vec3 to = src[2] + a * (src[0] - src[2]) + b * (src[1] - src[2]);
      // Two-sided for the benchmark: face each end towards the other.
      Vec3 nf = glm::dot(n_from, to - from) < 0.0f ? -n_from : n_from;
      Vec3 nt = glm::dot(n_src, from - to) < 0.0f ? -n_src : n_src;
      out.push_back(make_shadow_segment(from, nf, to, nt, offset));
    }
  }
  return out;
}

const BenchScene& scene(SceneKind kind, uint64_t triangles) {
  static std::map<std::pair<SceneKind, uint64_t>, std::unique_ptr<BenchScene>> cache;
  auto& slot = cache[{kind, triangles}];
  if (!slot) {
    slot = std::make_unique<BenchScene>();
    slot->hierarchy = build_hierarchy(generate_scene(kind, triangles, 1));
    slot->segments = vertex_to_source_segments(slot->hierarchy, 2);
  }
  return *slot;
}

void run(benchmark::State& state, const BenchScene& s, const VisibilityBackend& backend) {
  std::vector<uint8_t> out(kSamples);
  VisibilityStats stats;
  size_t vertex = 0;
  const ScopedFlushDenormals ftz;  // as the solver sets it around its loops
  for (auto _ : state) {
    backend.occluded(std::span(s.segments).subspan(vertex * kSamples, kSamples), out, stats);
    benchmark::DoNotOptimize(out.data());
    vertex = (vertex + 1) % kVertices;
  }
  state.SetItemsProcessed(int64_t(stats.rays));
  double rays = double(std::max<uint64_t>(stats.rays, 1));
  state.counters["occluded"] = double(stats.occluded) / rays;
  state.counters["triangles"] = double(s.hierarchy.triangles.size());
  if (backend.kind() == BackendKind::Grid) {
    state.counters["boxes/ray"] = double(stats.box_trials) / rays;
    state.counters["cells/ray"] = double(stats.cells_visited) / rays;
    state.counters["tests/ray"] = double(stats.triangle_tests) / rays;
  }
}

void register_all(uint64_t triangles, bool grid_sweep) {
  const SceneKind kinds[] = {SceneKind::CornellBox, SceneKind::Soup,
                             SceneKind::Nested,     SceneKind::TeapotInStadium,
                             SceneKind::Building,   SceneKind::FurnishedRoom};
  for (SceneKind kind : kinds) {
    std::string scene_name = std::string(to_string(kind)) + "_" + std::to_string(triangles);
    struct Config {
      std::string name;
      BackendKind backend;
      bool packets;
      double density;
    };
    std::vector<Config> configs = {{"embree/single", BackendKind::Embree, false, 0},
                                   {"embree/packet", BackendKind::Embree, true, 0},
                                   {"grid", BackendKind::Grid, false, kDefaultCellsPerTriangle}};
    if (grid_sweep) {
      for (double d : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0}) {
        configs.push_back({"grid@" + std::to_string(int(d)), BackendKind::Grid, false, d});
      }
    }
    for (const Config& c : configs) {
      benchmark::RegisterBenchmark((c.name + "/" + scene_name).c_str(),
                                   [kind, triangles, c](benchmark::State& state) {
                                     const BenchScene& s = scene(kind, triangles);
                                     std::unique_ptr<VisibilityBackend> backend =
                                         c.backend == BackendKind::Grid
                                             ? make_grid_backend(s.hierarchy, {}, c.density)
                                             : make_visibility_backend(c.backend, s.hierarchy,
                                                                       {.packets = c.packets});
                                     run(state, s, *backend);
                                   })
          ->MinTime(0.5);
    }
  }
  // Brute force only on a small scene: it is O(triangles) per ray.
  benchmark::RegisterBenchmark("brute/cornell_2000", [](benchmark::State& state) {
    const BenchScene& s = scene(SceneKind::CornellBox, 2000);
    auto backend = make_visibility_backend(BackendKind::Brute, s.hierarchy);
    run(state, s, *backend);
  })->MinTime(0.5);
}

}  // namespace
}  // namespace rad

int main(int argc, char** argv) {
  const char* size = std::getenv("RAD_BENCH_TRIANGLES");
  const char* sweep = std::getenv("RAD_BENCH_GRID_SWEEP");
  rad::register_all(size ? std::strtoull(size, nullptr, 10) : 100000,
                    sweep && std::string(sweep) == "1");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
