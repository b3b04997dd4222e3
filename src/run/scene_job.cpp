#include "run/scene_job.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/atomic_file.h"
#include "core/fingerprint.h"
#include "core/interrupt.h"
#include "core/memory.h"
#include "core/progress.h"
#include "export/exposure.h"
#include "export/mesh_file.h"
#include "export/output_mesh.h"
#include "export/seams.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "run/output_files.h"
#include "run/prepared_solve.h"
#include "run/report.h"
#include "run/scene_checks.h"
#include "run/write_outputs.h"
#include "scene/scene_file.h"
#include "solver/checkpoint.h"
#include "solver/distribute.h"
#include "solver/memory_estimate.h"

namespace rad {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

uint64_t job_fingerprint(const RunOptions& run, const SceneJob& job, const Hierarchy& h) {
  Fingerprint f;
  f.add(std::string_view(RAD_VERSION)).add(solve_fingerprint(h, run.solver, run.backend));
  f.add(run.solver.converge).add(run.solver.max_shots).add(run.solver.time_limit);
  f.add(job.outputs.ascii)
      .add(job.outputs.ambient)
      .add(job.outputs.tonemap)
      .add(job.outputs.exposure);
  f.add(job.outputs.image_width).add(job.outputs.image_height).add(job.outputs.camera.has_value());
  if (job.outputs.camera) f.add(*job.outputs.camera);
  f.add(std::string_view(job.outputs.mesh)).add(uint64_t(job.outputs.images.size()));
  for (const std::string& i : job.outputs.images) f.add(std::string_view(i));
  return f.value();
}

namespace {
// Every file the job writes, refused before any work if it cannot be written.
void check_job_outputs(const SceneJob& job) {
  check_outputs(job.outputs);
  if (!job.stats_json.empty()) check_writable(job.stats_json);
  if (!job.checkpoint.empty()) check_writable(job.checkpoint);
}
}  // namespace

SceneJobResult run_scene_job(const RunOptions& run, const SceneJob& job, Ranks* ranks) {
  const auto start = Clock::now();
  // Under MPI rank 0 speaks and writes; the others solve their share quietly.
  const bool lead = !ranks || ranks->rank() == 0;
  const bool quiet = run.quiet || !lead;
  Progress progress(quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
  // Stages go to stdout as the original printed them; the progress bar lives on stderr.
  auto say = [&](const std::string& s) {
    if (quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  RunTimes times;
  // Rank 0 alone writes, on its own machine.
  if (lead) check_job_outputs(job);
  check_scene_input(job.input);
  if (is_original_output_name(job.outputs.mesh)) {
    say(job.outputs.mesh + ": .gfo is the original's output name; writing Geomview COFF there");
  }

  say("Reading description file...");
  const Hierarchy hierarchy = load_hierarchy(job.input.path, job.input.model, job.input.hierarchy);
  require_light(hierarchy, job.input, run.solver);
  times.parse = since(start);
  const uint64_t job_id = job.stats_json.empty() ? 0 : job_fingerprint(run, job, hierarchy);
  if (job.skip_if_done && job_id != 0 && read_job_fingerprint(job.stats_json) == job_id) {
    bool complete = job.outputs.mesh.empty() || std::filesystem::exists(job.outputs.mesh);
    for (const std::string& image : job.outputs.images) complete &= std::filesystem::exists(image);
    if (complete) {
      say("Outputs complete from an earlier run with the same scene and options: skipped");
      SceneJobResult r;
      r.skipped = true;
      r.seconds = since(start);
      return r;
    }
  }

  say("Initializing...");
  auto t = Clock::now();
  const PreparedSolve prepared(hierarchy, run);
  const int threads = prepared.threads();
  // No edits here: the log keeps the major shots only.
  SolverOptions solver = run.solver;
  solver.log_minor_shots = false;
  SolverState state = make_solver_state(hierarchy, solver);

  const uint64_t fingerprint =
      job.checkpoint.empty() && !ranks ? 0 : solve_fingerprint(hierarchy, run.solver, run.backend);
  if (!job.checkpoint.empty()) remove_stale_temporaries(job.checkpoint);
  if (!job.checkpoint.empty() && std::filesystem::exists(job.checkpoint)) {
    read_checkpoint(job.checkpoint, state, fingerprint);
    say(fmt::format("Resuming from checkpoint {} ({} shots done)", job.checkpoint, state.shots));
  }
  // The mesh only grows by subdivision, down to --min-size: refuse a solve that could outgrow
  // the memory before spending any time on it, and stop one that reaches it. Under MPI the
  // machine's memory is shared by its ranks, and rank 0 holds the whole mesh at the end (the
  // bound is the whole scene's on every rank).
  const size_t memory_limit = solve_memory_limit(job.max_memory, ranks != nullptr);
  const double growth = worst_case_growth_bytes(state);
  if (ranks) distribute(state, *ranks, fingerprint ^ uint64_t(ranks->size()));
  times.build = since(t);
  const double now = double(resident_bytes());
  double per_shot = 0.0;
  for (size_t c = 0; c < state.clusters.size(); ++c)
    per_shot = std::max(per_shot, shot_log_bytes(state, c));
  if (memory_limit > 0 && now + growth > double(memory_limit)) {
    throw Error(SourceLoc{job.input.path},
                fmt::format("this solve could need {} ({} now, {} more if every element were "
                            "split down to the smallest size, {:.3g}), over the limit of {}{}; "
                            "raise --min-size, or give --max-memory to run anyway (the solve then "
                            "stops at that limit and writes what it has)",
                            format_bytes(now + growth), format_bytes(now), format_bytes(growth),
                            state.min_size, format_bytes(double(memory_limit)),
                            job.max_memory > 0 ? " (--max-memory)" : " (90% of this machine's)"));
  }
  limit_kept_answers(state.options, memory_limit);
  say(fmt::format(
      "Memory: {} now, at most {} more by subdivision, {} per major shot logged and {} of "
      "kept shadow-ray answers (limit {})",
      format_bytes(now), format_bytes(growth), format_bytes(per_shot),
      format_bytes(double(state.options.kept_rays_bytes)), format_bytes(double(memory_limit))));

  say(fmt::format("Starting Computation ({} triangles, {} backend, {} thread{}{})",
                  hierarchy.triangles.size(), to_string(run.backend), threads,
                  threads == 1 ? "" : "s",
                  ranks ? fmt::format(" on each of {} MPI ranks", ranks->size()) : ""));
  t = Clock::now();
  auto saved = Clock::now();
  // Under MPI rank 0 writes the checkpoint of the whole state (the same file one process
  // writes, so either resumes it), gathered from the ranks; between shots it then releases the
  // other ranks' polygons again.
  const auto save = [&](bool last) -> std::vector<RankReport> {
    std::vector<RankReport> reports;
    if (job.checkpoint.empty()) return reports;
    if (ranks) {
      reports = collect(state);
      if (lead) {
        const SolverStats own = state.stats;
        const double absorbed = state.absorbed_energy;
        state.stats = total_stats(reports), state.absorbed_energy = total_absorbed(reports);
        write_checkpoint(job.checkpoint, state, fingerprint);
        if (!last) state.stats = own, state.absorbed_energy = absorbed, release_foreign(state);
      }
    } else {
      write_checkpoint(job.checkpoint, state, fingerprint);
    }
    saved = Clock::now();
    return reports;
  };
  const double log_goal = std::log(std::max(run.solver.converge, 1e-12));
  install_interrupt_handlers();
  const StopReason stop = solve(
      state, prepared.visibility(),
      [&](const SolverState& s, const ShotRecord& r) {
        const double f = r.unshot_fraction > 0 ? std::log(r.unshot_fraction) / log_goal : 1.0;
        progress.update(f, fmt::format("shot {}  unshot {:.2e}  subdivisions {}", r.shot,
                                       r.unshot_fraction, s.stats.subdivisions));
        bool due = !job.checkpoint.empty() && since(saved) >= job.checkpoint_every;
        if (ranks && !job.checkpoint.empty()) due = ranks->max(due && lead) > 0;  // rank 0's clock
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
  if (ranks && job.checkpoint.empty()) {
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
                    job.checkpoint.empty() ? "" : " (resume with the same command)"));
  }

  t = Clock::now();
  const OutputMesh mesh = make_output_mesh(state, job.outputs.ambient);
  StagedFiles files;
  write_outputs(mesh, job.outputs,
                scene_tone_map(state, mesh.display, job.outputs.tonemap, job.outputs.exposure), say,
                files);
  times.write = since(t);
  times.total = since(start);
  // Last: rad batch takes a stats file with this job's fingerprint to mean every output is there.
  if (!job.stats_json.empty()) {
    files.write(job.stats_json, [&](const std::string& path) {
      write_stats_json(path, run, job, state, stop, times, measure_seams(mesh, hierarchy.triangles),
                       job_id, reports);
    });
  }
  files.commit();
  if (!quiet) std::fputs(format_statistics(state, times.total).c_str(), stdout);
  return {stop, state.shots, count_vertices(state.mesh), state.unshot_fraction(), times.total};
}

}  // namespace rad
