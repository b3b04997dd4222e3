// The solver at work (Google Benchmark, JSON with --benchmark_format=json): one shot over every
// receiving vertex (receivers/s as items_per_second, shadow rays/s), the same shot's shadow
// segments replayed raw through each backend (the rtcOccluded1 rate to divide by), refinement
// after a shot, solver-state bytes per vertex, and the Cornell box solved end to end.
//
//   solver_bench [--benchmark_filter=...] [--benchmark_out=solver.json]
//   RAD_BENCH_TRIANGLES=50000   size of the generated scenes (default 50000: >= 100k receivers)
//   RAD_BENCH_LATER_SHOT=10     which shot stands for a "typical" later one (default 10)
//   RAD_BENCH_LARGE=1           also the first shot of the 1M-triangle building
//   RAD_BENCH_CORNELL=PATH      scene of the end-to-end solve (default scenes/cornell_box.des)
//
// Names read kind/scene/backend/shot/threads, e.g. shot/cornell_50000/embree-packet/first/t2.
// Threads are limited with tbb::global_control inside each benchmark; times are wall-clock.
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/denormals.h"
#include "core/error.h"
#include "scene/parser.h"
#include "scenegen/scenegen.h"
#include "solver/refine.h"
#include "solver/shoot.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

// The backends as the benchmarks name them.
enum class Variant { EmbreePacket, EmbreeSingle, Grid };
const char* to_string(Variant v) {
  switch (v) {
    case Variant::EmbreePacket:
      return "embree-packet";
    case Variant::EmbreeSingle:
      return "embree-single";
    case Variant::Grid:
      return "grid";
  }
  return "?";
}

std::unique_ptr<VisibilityBackend> make_backend(Variant v, const Hierarchy& h) {
  switch (v) {
    case Variant::EmbreePacket:
      return make_visibility_backend(BackendKind::Embree, h, {true});
    case Variant::EmbreeSingle:
      return make_visibility_backend(BackendKind::Embree, h, {false});
    case Variant::Grid:
      return make_visibility_backend(BackendKind::Grid, h, {false});
  }
  return nullptr;
}

// Passes every batch to `inner` and keeps a copy of its segments, per thread.
class RecordingBackend final : public VisibilityBackend {
 public:
  struct Batches {
    std::vector<Segment> segments;
    std::vector<size_t> sizes;
  };
  explicit RecordingBackend(const VisibilityBackend& inner) : inner_(inner) {}
  BackendKind kind() const override { return inner_.kind(); }
  void occluded(std::span<const Segment> segments, std::span<uint8_t> out,
                VisibilityStats& stats) const override {
    inner_.occluded(segments, out, stats);
    Batches& b = recorded_.local();
    b.segments.insert(b.segments.end(), segments.begin(), segments.end());
    b.sizes.push_back(segments.size());
  }
  SegmentHit first_hit(const Segment& segment, VisibilityStats& stats) const override {
    return inner_.first_hit(segment, stats);
  }
  const tbb::enumerable_thread_specific<Batches>& recorded() const { return recorded_; }

 private:
  const VisibilityBackend& inner_;
  mutable tbb::enumerable_thread_specific<Batches> recorded_;
};

// Heap bytes of one allocation as malloc holds it (usable size plus its 8-byte header).
size_t heap_bytes(const void* p) { return p ? malloc_usable_size(const_cast<void*>(p)) + 8 : 0; }
template <typename T>
size_t heap_bytes(const std::vector<T>& v) {
  return v.capacity() ? heap_bytes(v.data()) : 0;
}

/// Bytes the solver state holds on the heap and inline, from the vectors' capacities (the hash
/// maps of midpoints estimated: 8 bytes per bucket, a 32-byte chunk per node), by part.
struct StateBytes {
  size_t polygon_structs = 0;  // the PolygonMesh records themselves (vector headers, map)
  size_t vertex_arrays = 0;    // position, irradiance, unshot, shot, major
  size_t elements = 0;
  size_t midpoints = 0;
  size_t other = 0;  // per-polygon energies, materials, the history (not the log of shot
                     // sources the solver keeps: 7 KB a shot at 16 samples, 30 KB at 64)
  size_t total() const { return polygon_structs + vertex_arrays + elements + midpoints + other; }
};

StateBytes solver_state_bytes(const SolverState& s) {
  StateBytes b;
  b.polygon_structs = heap_bytes(s.solution.mesh.polygons) + heap_bytes(s.solution.vertex_states);
  for (size_t q = 0; q < s.solution.mesh.polygons.size(); ++q) {
    const PolygonMesh& p = s.solution.mesh.polygons[q];
    b.vertex_arrays += heap_bytes(p.positions) + heap_bytes(s.solution.vertex_states[q]);
    b.elements += heap_bytes(p.elements);
    if (p.midpoints.size() > 0) {  // allocated at the first split: the map, buckets, nodes
      const auto& m = p.midpoints.entries();
      b.midpoints += sizeof(m) + 8 + m.bucket_count() * 8 + 8 + m.size() * 32;
    }
  }
  b.other = sizeof(SolverState) + heap_bytes(s.solution.materials) +
            heap_bytes(s.energy.unshot_energy) + heap_bytes(s.shots.history);
  for (const auto& g : s.scene.barycentric_grids) b.other += heap_bytes(g);
  const Clusters& k = s.scene.clusters;
  b.other += heap_bytes(k.first) + heap_bytes(k.polygons) + heap_bytes(k.cluster_of) +
             heap_bytes(k.edge_first) + heap_bytes(k.edge_a) + heap_bytes(k.edge_b) +
             k.size() * (2 * sizeof(Vec3) + 7 * sizeof(float) + sizeof(Aabb) + 1);
  return b;
}

/// The state's bytes and vertex count, measured on the solver's own state (a copy would hold
/// tighter capacities than the grown vectors).
struct StateSize {
  StateBytes bytes;
  size_t vertices = 0;
};
StateSize state_size(const SolverState& s) {
  return {solver_state_bytes(s), count_vertices(s.solution.mesh)};
}

/// Per-vertex state bytes as counters: the total and its parts.
void state_counters(benchmark::State& st, const StateSize& size) {
  const double v = double(std::max<size_t>(size.vertices, 1));
  const StateBytes& b = size.bytes;
  st.counters["state_bytes/vertex"] = double(b.total()) / v;
  st.counters["polygon_structs_bytes/vertex"] = double(b.polygon_structs) / v;
  st.counters["vertex_arrays_bytes/vertex"] = double(b.vertex_arrays) / v;
  st.counters["elements_bytes/vertex"] = double(b.elements) / v;
  st.counters["midpoints_bytes/vertex"] = double(b.midpoints) / v;
  st.counters["other_bytes/vertex"] = double(b.other) / v;
  st.counters["vertices"] = v;
}

/// One shot ready to be timed again and again.
struct ShotCase {
  int64_t index = 0;   // 1-based shot number
  SolverState before;  // the shooter chosen and its unshot radiosity cleared (step()'s start)
  ShotSource src;
  bool major = false;
  size_t receivers = 0;             // vertices of the polygons the shot reaches
  std::vector<Segment> segments;    // every shadow segment the shot casts, batch after batch
  std::vector<size_t> batch_start;  // batch b = [batch_start[b], batch_start[b + 1])
  SolverState after;                // `before` after the shot, ready for refinement
  std::vector<uint8_t> received;
  StateSize size_before;   // the state before the shot
  StateSize size_refined;  // after the shot and its refinement
};

// Does what step() does before shooting, then shoots once through a recorder.
std::unique_ptr<ShotCase> prepare_shot(SolverState s, const VisibilityBackend& vis) {
  auto c = std::make_unique<ShotCase>();
  const std::optional<Shooter> shooter = choose_shooter(s);
  if (!shooter) return nullptr;
  c->index = s.shots.count + 1;
  c->src = make_shot_source(s, shooter->cluster);
  const Clusters& k = s.scene.clusters;
  const std::span<const uint32_t> own(k.polygons.data() + k.first[size_t(shooter->cluster)],
                                      k.polygon_count(size_t(shooter->cluster)));
  for (uint32_t p : own)
    for (VertexState& v : s.solution.vertex_states[p]) v.unshot = Vec3(0.0f);
  c->major = s.options.major_shot_fraction > 0.0 &&
             shooter->energy >= s.options.major_shot_fraction * s.energy.emitted_energy;
  set_unshot_energies(s.energy, s.solution, s.scene.clusters, own,
                      std::vector<UnshotEnergy>(own.size()));
  share_unshot_totals(s.energy, s.ownership.ranks);
  c->before = s;
  c->size_before = state_size(s);
  RecordingBackend recorder(vis);
  shoot_to_receivers({s.options, s.scene, s.energy, s.shots, s.ownership, s.solution, s.receivers,
                      s.kept, s.stats},
                     c->src, recorder, c->major);
  c->received = s.receivers.marked;
  c->after = s;
  refine_after_shot(
      {s.options, s.energy, s.shots, s.solution, s.scene, s.stats}, s.receivers, c->src, vis,
      c->major, needing_refinement(s.options, s.energy, s.scene, s.solution, s.receivers.polygons));
  c->size_refined = state_size(s);
  for (size_t p = 0; p < c->received.size(); ++p) {
    if (c->received[p]) c->receivers += c->after.solution.mesh.polygons[p].vertex_count();
  }
  c->batch_start.push_back(0);
  for (const RecordingBackend::Batches& b : recorder.recorded()) {
    c->segments.insert(c->segments.end(), b.segments.begin(), b.segments.end());
    for (size_t n : b.sizes) c->batch_start.push_back(c->batch_start.back() + n);
  }
  return c;
}

uint64_t env_u64(const char* name, uint64_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

/// A scene by name: generated (kind_triangles) or read from a description file.
struct SceneSpec {
  std::string name;
  std::function<SceneDescription()> make;
};

/// A scene, its backends, and its first and later shots, built on first use.
struct SceneCase {
  Hierarchy hierarchy;
  std::map<Variant, std::unique_ptr<VisibilityBackend>> backends;
  std::unique_ptr<ShotCase> first, later;

  const VisibilityBackend& backend(Variant v) {
    auto& b = backends[v];
    if (!b) b = make_backend(v, hierarchy);
    return *b;
  }
  const ShotCase& shot(bool is_later) {
    std::unique_ptr<ShotCase>& slot = is_later ? later : first;
    if (slot) return *slot;
    SolverState s = make_solver_state(hierarchy, SolverOptions{});
    if (is_later) {
      const int64_t n = int64_t(env_u64("RAD_BENCH_LATER_SHOT", 10));
      while (s.shots.count + 1 < n && step(s, backend(Variant::EmbreePacket))) {
      }
    }
    slot = prepare_shot(std::move(s), backend(Variant::EmbreePacket));
    if (!slot) throw Error("nothing to shoot in the benchmark scene");
    return *slot;
  }
};

SceneCase& scene_case(const SceneSpec& spec) {
  static std::map<std::string, std::unique_ptr<SceneCase>> cache;
  auto& slot = cache[spec.name];
  if (!slot) {
    slot = std::make_unique<SceneCase>();
    slot->hierarchy = build_hierarchy(spec.make());
  }
  return *slot;
}

void common_counters(benchmark::State& st, const SceneCase& sc, const ShotCase& c, int threads) {
  st.counters["threads"] = threads;
  st.counters["triangles"] = double(sc.hierarchy.triangles.size());
  st.counters["receivers"] = double(c.receivers);
  st.counters["shot_index"] = double(c.index);
  st.counters["recorded_rays"] = double(c.segments.size());
}

// One shot: shoot_to_receivers over every other polygon, as the solver calls it.
void bm_shot(benchmark::State& st, const SceneSpec& spec, bool later, Variant v, int threads) {
  SceneCase& sc = scene_case(spec);
  const ShotCase& c = sc.shot(later);
  const VisibilityBackend& vis = sc.backend(v);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  SolverState s = c.before;
  const SolverStats start = s.stats;
  for (auto _ : st) {
    shoot_to_receivers({s.options, s.scene, s.energy, s.shots, s.ownership, s.solution, s.receivers,
                        s.kept, s.stats},
                       c.src, vis, c.major);
  }
  const double n = double(st.iterations());
  const double rays = double(s.stats.rays.rays - start.rays.rays);
  st.SetItemsProcessed(int64_t(st.iterations()) * int64_t(c.receivers));
  st.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  st.counters["rays/shot"] = rays / n;
  st.counters["cuts/shot"] = double(s.stats.intensity_cuts - start.intensity_cuts) / n;
  st.counters["evaluations/shot"] =
      double(s.stats.vertex_evaluations - start.vertex_evaluations) / n;
  st.counters["occluded"] =
      double(s.stats.rays.occluded - start.rays.occluded) / std::max(rays, 1.0);
  state_counters(st, c.size_before);
  common_counters(st, sc, c, threads);
}

// The shot's own segments, batch by batch (one batch per receiving vertex, as the solver makes
// them), through a backend with nothing else around: the raw rate.
void bm_raw(benchmark::State& st, const SceneSpec& spec, bool later, Variant v, int threads) {
  SceneCase& sc = scene_case(spec);
  const ShotCase& c = sc.shot(later);
  const VisibilityBackend& vis = sc.backend(v);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  std::vector<uint8_t> out(c.segments.size());
  tbb::enumerable_thread_specific<VisibilityStats> stats;
  const size_t batches = c.batch_start.size() - 1;
  const std::span<const Segment> all(c.segments);
  for (auto _ : st) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches, 8), [&](const auto& r) {
      const ScopedFlushDenormals ftz;  // as the solver does: the raw rate gets the same saving
      VisibilityStats& local = stats.local();
      for (size_t b = r.begin(); b != r.end(); ++b) {
        const size_t at = c.batch_start[b], len = c.batch_start[b + 1] - at;
        vis.occluded(all.subspan(at, len), std::span(out).subspan(at, len), local);
      }
    });
  }
  VisibilityStats total;
  for (const VisibilityStats& s : stats) total += s;
  st.SetItemsProcessed(int64_t(total.rays));
  st.counters["rays/s"] = benchmark::Counter(double(total.rays), benchmark::Counter::kIsRate);
  st.counters["rays/batch"] = double(c.segments.size()) / double(std::max<size_t>(batches, 1));
  st.counters["occluded"] = double(total.occluded) / double(std::max<uint64_t>(total.rays, 1));
  common_counters(st, sc, c, threads);
}

// Adaptive subdivision after the shot (the split, the exact midpoints' gathers): manual time,
// so copying the state back before each run is not counted.
void bm_refine(benchmark::State& st, const SceneSpec& spec, bool later, int threads) {
  SceneCase& sc = scene_case(spec);
  const ShotCase& c = sc.shot(later);
  const VisibilityBackend& vis = sc.backend(Variant::EmbreePacket);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  double splits = 0, rays = 0;
  for (auto _ : st) {
    SolverState s = c.after;
    const auto t0 = std::chrono::steady_clock::now();
    refine_after_shot(  // over c.after's receivers
        {s.options, s.energy, s.shots, s.solution, s.scene, s.stats}, s.receivers, c.src, vis,
        c.major,
        needing_refinement(s.options, s.energy, s.scene, s.solution, s.receivers.polygons));
    const auto t1 = std::chrono::steady_clock::now();
    st.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
    splits += double(s.stats.subdivisions - c.after.stats.subdivisions);
    rays += double(s.stats.rays.rays - c.after.stats.rays.rays);
  }
  st.SetItemsProcessed(int64_t(splits));  // subdivisions per second
  st.counters["splits/shot"] = splits / double(st.iterations());
  st.counters["rays/shot"] = rays / double(st.iterations());
  st.counters["new_vertices"] = double(c.size_refined.vertices - c.size_before.vertices);
  state_counters(st, c.size_refined);
  common_counters(st, sc, c, threads);
}

// The Cornell box from the description file to the default convergence, all cores.
void bm_cornell_solve(benchmark::State& st, const std::string& path, int threads) {
  const Hierarchy h = build_hierarchy(parse_scene_file(path));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const auto vis = make_backend(Variant::EmbreePacket, h);
  SolverState s;
  for (auto _ : st) {
    s = make_solver_state(h, SolverOptions{});
    benchmark::DoNotOptimize(solve(s, *vis));
  }
  st.counters["threads"] = threads;
  st.counters["shots"] = double(s.shots.count);
  st.counters["rays"] = double(s.stats.rays.rays);
  st.counters["shoot_seconds"] = s.stats.shoot_seconds;
  st.counters["refine_seconds"] = s.stats.refine_seconds;
  st.counters["unshot_fraction"] = s.energy.unshot_fraction();
  state_counters(st, state_size(s));
}

// Pure arithmetic in parallel, no memory traffic: the speed-up the machine offers right now
// (other processes share the cores), to read the shots' speed-ups against.
void bm_spin(benchmark::State& st, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  constexpr size_t kChunks = 64, kSteps = 1 << 18;
  std::vector<uint64_t> out(kChunks);
  for (auto _ : st) {
    tbb::parallel_for(size_t(0), kChunks, [&](size_t c) {
      uint64_t x = c + 1;
      for (size_t i = 0; i < kSteps; ++i) x = x * 6364136223846793005ull + 1442695040888963407ull;
      out[c] = x;
    });
    benchmark::DoNotOptimize(out.data());
  }
  st.SetItemsProcessed(int64_t(st.iterations() * kChunks * kSteps));
  st.counters["threads"] = threads;
}

SceneSpec generated(SceneKind kind, uint64_t triangles) {
  return {std::string(to_string(kind)) + "_" + std::to_string(triangles),
          [=] { return generate_scene(kind, triangles, 1); }};
}

void register_all() {
  const uint64_t n = env_u64("RAD_BENCH_TRIANGLES", 50000);
  const int all = tbb::info::default_concurrency();
  std::vector<int> thread_counts = {1};
  if (all >= 2) thread_counts.push_back(2);
  const char* cornell_env = std::getenv("RAD_BENCH_CORNELL");
  const std::string cornell =
      cornell_env && *cornell_env ? cornell_env : RAD_SOURCE_DIR "/scenes/cornell_box.des";
  // The bundled Cornell box (34 triangles: refinement at work) and the generated families at
  // n triangles (the soup has no light).
  std::vector<SceneSpec> scenes = {{"cornell_box", [=] { return parse_scene_file(cornell); }}};
  for (SceneKind k : {SceneKind::CornellBox, SceneKind::Nested, SceneKind::TeapotInStadium,
                      SceneKind::Building}) {
    scenes.push_back(generated(k, n));
  }
  auto name = [](const char* what, const SceneSpec& spec, const char* backend, bool later,
                 int threads) {
    return std::string(what) + "/" + spec.name + "/" + backend + "/" + (later ? "later" : "first") +
           "/t" + std::to_string(threads);
  };
  // Wall-clock time (TBB works on other threads); `once` for runs of seconds.
  auto timed = [](const std::string& nm, auto fn, bool once = false) {
    auto* b = benchmark::RegisterBenchmark(nm.c_str(), fn)->UseRealTime();
    if (once) {
      b->Iterations(1);
    } else {
      b->MinTime(0.3);
    }
    b->Unit(benchmark::kMillisecond);
  };
  // Manual time: the benchmark times only the part it measures.
  auto manual = [](const std::string& nm, auto fn, bool once = false) {
    auto* b = benchmark::RegisterBenchmark(nm.c_str(), fn)->UseManualTime();
    if (once) {
      b->Iterations(1);
    } else {
      b->MinTime(0.3);
    }
    b->Unit(benchmark::kMillisecond);
  };
  auto spin = [&](const char* when) {
    for (int t : thread_counts) {
      timed(std::string("calib/spin/-/") + when + "/t" + std::to_string(t),
            [=](benchmark::State& st) { bm_spin(st, t); });
    }
  };
  spin("start");
  for (const SceneSpec& sc : scenes) {
    for (bool later : {false, true}) {
      for (Variant v : {Variant::EmbreePacket, Variant::EmbreeSingle, Variant::Grid}) {
        for (int t : thread_counts) {
          timed(name("shot", sc, to_string(v), later, t),
                [=](benchmark::State& st) { bm_shot(st, sc, later, v, t); });
          timed(name("raw", sc, to_string(v), later, t),
                [=](benchmark::State& st) { bm_raw(st, sc, later, v, t); });
        }
      }
      for (int t : thread_counts) {
        manual(name("refine", sc, "embree-packet", later, t),
               [=](benchmark::State& st) { bm_refine(st, sc, later, t); });
      }
    }
  }
  if (env_u64("RAD_BENCH_LARGE", 0) == 1) {
    // The 1M-triangle building: its first shot on all cores, the raw rates, refinement.
    const SceneSpec big = generated(SceneKind::Building, 1000000);
    for (Variant v : {Variant::EmbreePacket, Variant::EmbreeSingle}) {
      timed(name("shot", big, to_string(v), false, all),
            [=](benchmark::State& st) { bm_shot(st, big, false, v, all); });
      timed(name("raw", big, to_string(v), false, all),
            [=](benchmark::State& st) { bm_raw(st, big, false, v, all); });
    }
    manual(
        name("refine", big, "embree-packet", false, all),
        [=](benchmark::State& st) { bm_refine(st, big, false, all); }, true);
  }
  spin("end");
  timed(
      "solve/cornell_box/embree-packet/converged/t" + std::to_string(all),
      [=](benchmark::State& st) { bm_cornell_solve(st, cornell, all); }, true);
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
