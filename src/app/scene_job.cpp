#include "app/scene_job.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/report.h"
#include "core/atomic_file.h"
#include "core/fingerprint.h"
#include "core/interrupt.h"
#include "core/memory.h"
#include "core/progress.h"
#include "export/exposure.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"
#include "export/output_mesh.h"
#include "export/seams.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "scene/scene_file.h"
#include "solver/checkpoint.h"
#include "solver/distribute.h"
#include "solver/memory_estimate.h"
#include "visibility/backend.h"

namespace rad {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

uint64_t job_fingerprint(const CommandLine& cmd, const SceneJob& job, const Hierarchy& h) {
  Fingerprint f;
  f.add(std::string_view(RAD_VERSION)).add(solve_fingerprint(h, cmd.solver, cmd.backend));
  f.add(cmd.solver.converge).add(cmd.solver.max_shots).add(cmd.solver.time_limit);
  f.add(cmd.ascii).add(cmd.ambient).add(cmd.tonemap).add(cmd.exposure);
  f.add(cmd.image_width).add(cmd.image_height).add(cmd.camera.has_value());
  if (cmd.camera) f.add(*cmd.camera);
  f.add(std::string_view(job.mesh_output)).add(uint64_t(job.images.size()));
  for (const std::string& i : job.images) f.add(std::string_view(i));
  return f.value();
}

SceneJobResult run_scene_job(const CommandLine& cmd, const SceneJob& job, Ranks* ranks) {
  const auto start = Clock::now();
  // Under MPI rank 0 speaks and writes; the others solve their share quietly.
  const bool lead = !ranks || ranks->rank() == 0;
  const bool quiet = cmd.quiet || !lead;
  Progress progress(quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
  // Stages go to stdout as the original printed them; the progress bar lives on stderr.
  auto say = [&](const std::string& s) {
    if (quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  RunTimes times;
  if (!job.mesh_output.empty()) check_mesh_extension(job.mesh_output);
  if (is_original_output_name(job.mesh_output)) {
    say(job.mesh_output + ": .gfo is the original's output name; writing Geomview COFF there");
  }
  for (const std::string& image : job.images) check_image_extension(image);

  say("Reading description file...");
  const Hierarchy hierarchy = load_hierarchy(job.scene, cmd.model, cmd.hierarchy);
  times.parse = since(start);
  const uint64_t job_id = job.stats_json.empty() ? 0 : job_fingerprint(cmd, job, hierarchy);
  if (job.skip_if_done && job_id != 0 && read_job_fingerprint(job.stats_json) == job_id) {
    bool complete = job.mesh_output.empty() || std::filesystem::exists(job.mesh_output);
    for (const std::string& image : job.images) complete &= std::filesystem::exists(image);
    if (complete) {
      say("Outputs complete from an earlier run with the same scene and options: skipped");
      SceneJobResult r;
      r.skipped = true;
      r.seconds = since(start);
      return r;
    }
  }

  say("Initializing...");
  const int threads = thread_count(cmd);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  auto t = Clock::now();
  const std::unique_ptr<VisibilityBackend> visibility =
      make_visibility_backend(cmd.backend, hierarchy, VisibilityOptions{cmd.packets});
  SolverState state = make_solver_state(hierarchy, cmd.solver);

  const uint64_t fingerprint =
      cmd.checkpoint.empty() && !ranks ? 0 : solve_fingerprint(hierarchy, cmd.solver, cmd.backend);
  if (!cmd.checkpoint.empty()) remove_stale_temporaries(cmd.checkpoint);
  if (!cmd.checkpoint.empty() && std::filesystem::exists(cmd.checkpoint)) {
    read_checkpoint(cmd.checkpoint, state, fingerprint);
    say(fmt::format("Resuming from checkpoint {} ({} shots done)", cmd.checkpoint, state.shots));
  }
  // The mesh only grows by subdivision, down to --min-size: refuse a solve that could outgrow
  // the memory before spending any time on it, and stop one that reaches it. Under MPI the
  // machine's memory is shared by its ranks, and rank 0 holds the whole mesh at the end (the
  // bound is the whole scene's on every rank).
  const size_t memory_limit =
      cmd.max_memory > 0
          ? cmd.max_memory
          : size_t(0.9 * double(machine_memory_bytes()) / double(ranks ? local_rank_count() : 1));
  const double growth = worst_case_growth_bytes(state);
  if (ranks) distribute(state, *ranks, fingerprint ^ uint64_t(ranks->size()));
  times.build = since(t);
  const double now = double(resident_bytes());
  double per_shot = 0.0;
  for (size_t c = 0; c < state.clusters.size(); ++c)
    per_shot = std::max(per_shot, shot_log_bytes(state, c));
  if (memory_limit > 0 && now + growth > double(memory_limit)) {
    throw Error(SourceLoc{job.scene},
                fmt::format("this solve could need {} ({} now, {} more if every element were "
                            "split down to the smallest size, {:.3g}), over the limit of {}{}; "
                            "raise --min-size, or give --max-memory to run anyway (the solve then "
                            "stops at that limit and writes what it has)",
                            format_bytes(now + growth), format_bytes(now), format_bytes(growth),
                            state.min_size, format_bytes(double(memory_limit)),
                            cmd.max_memory > 0 ? " (--max-memory)" : " (90% of this machine's)"));
  }
  say(
      fmt::format("Memory: {} now, at most {} more by subdivision and {} per shot logged "
                  "(limit {})",
                  format_bytes(now), format_bytes(growth), format_bytes(per_shot),
                  format_bytes(double(memory_limit))));

  say(fmt::format("Starting Computation ({} triangles, {} backend, {} thread{}{})",
                  hierarchy.triangles.size(), to_string(cmd.backend), threads,
                  threads == 1 ? "" : "s",
                  ranks ? fmt::format(" on each of {} MPI ranks", ranks->size()) : ""));
  t = Clock::now();
  auto saved = Clock::now();
  // Under MPI rank 0 writes the checkpoint of the whole state (the same file one process
  // writes, so either resumes it), gathered from the ranks; between shots it then releases the
  // other ranks' polygons again.
  const auto save = [&](bool last) -> std::vector<RankReport> {
    std::vector<RankReport> reports;
    if (cmd.checkpoint.empty()) return reports;
    if (ranks) {
      reports = collect(state);
      if (lead) {
        const SolverStats own = state.stats;
        const double absorbed = state.absorbed_energy;
        state.stats = total_stats(reports), state.absorbed_energy = total_absorbed(reports);
        write_checkpoint(cmd.checkpoint, state, fingerprint);
        if (!last) state.stats = own, state.absorbed_energy = absorbed, release_foreign(state);
      }
    } else {
      write_checkpoint(cmd.checkpoint, state, fingerprint);
    }
    saved = Clock::now();
    return reports;
  };
  const double log_goal = std::log(std::max(cmd.solver.converge, 1e-12));
  install_interrupt_handlers();
  const StopReason stop = solve(
      state, *visibility,
      [&](const SolverState& s, const ShotRecord& r) {
        const double f = r.unshot_fraction > 0 ? std::log(r.unshot_fraction) / log_goal : 1.0;
        progress.update(f, fmt::format("shot {}  unshot {:.2e}  subdivisions {}", r.shot,
                                       r.unshot_fraction, s.stats.subdivisions));
        bool due = !cmd.checkpoint.empty() && since(saved) >= cmd.checkpoint_every;
        if (ranks && !cmd.checkpoint.empty()) due = ranks->max(due && lead) > 0;  // rank 0's clock
        if (due) save(false);
      },
      [&]() -> std::optional<StopReason> {
        if (interrupt_signal()) return StopReason::Interrupted;
        if (memory_limit > 0 && resident_bytes() > memory_limit) return StopReason::MemoryLimit;
        return std::nullopt;
      });
  times.solve = since(t);
  t = Clock::now();
  // Rank 0 takes every rank's polygons and counters (once: with a checkpoint, its save does
  // it): from here on its state is whole.
  std::vector<RankReport> reports;
  if (ranks && cmd.checkpoint.empty()) {
    reports = collect(state);
    if (lead) state.stats = total_stats(reports), state.absorbed_energy = total_absorbed(reports);
  } else {
    reports = save(true);
  }
  if (!lead) return {stop, state.shots, 0, state.unshot_fraction(), since(start)};
  times.gather = ranks ? since(t) : 0.0;
  progress.finish(fmt::format("{} after {} shots", to_string(stop), state.shots));
  if (stop == StopReason::MemoryLimit) {
    say(fmt::format("Stopped at the memory limit ({}): writing the solution so far",
                    format_bytes(double(memory_limit))));
  }
  if (stop == StopReason::Interrupted) {
    say(fmt::format("Stopped by signal {}: writing the solution so far{}", interrupt_signal(),
                    cmd.checkpoint.empty() ? "" : " (resume with the same command)"));
  }

  t = Clock::now();
  const OutputMesh mesh = make_output_mesh(state, cmd.ambient);
  MeshFileOptions mo;
  mo.ascii = cmd.ascii;
  mo.tone = scene_tone_map(state, mesh.display, cmd.tonemap, cmd.exposure);
  if (!job.mesh_output.empty()) {
    say(fmt::format("Writing results in file {}", job.mesh_output));
    write_mesh_file(job.mesh_output, mesh, mo);
  }
  if (!job.images.empty()) {
    const RenderOptions ro{cmd.image_width, cmd.image_height};
    const Camera camera = cmd.camera ? *cmd.camera
                                     : default_camera(mesh.position(), mesh.indices(),
                                                      float(ro.width) / float(ro.height));
    const Image image = render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro);
    for (const std::string& path : job.images) {
      say(fmt::format("Writing image {}", path));
      write_image_file(path, image, mo.tone);
    }
  }
  times.write = since(t);
  times.total = since(start);
  if (!job.stats_json.empty()) {
    write_stats_json(job.stats_json, cmd, job.scene, state, stop, times,
                     measure_seams(mesh, hierarchy.triangles), job_id, reports);
  }
  if (!quiet) std::fputs(format_statistics(state, times.total).c_str(), stdout);
  return {stop, state.shots, count_vertices(state.mesh), state.unshot_fraction(), times.total};
}

}  // namespace rad
