#include "run/scene_job.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
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
#include "run/object_illuminance.h"
#include "run/output_files.h"
#include "run/prepared_solve.h"
#include "run/report.h"
#include "run/scene_checks.h"
#include "run/scene_unit.h"
#include "run/stage_camera.h"
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
  f.add(metres_per_unit(job.input));  // the statistics' areas and powers
  f.add(job.outputs.ascii)
      .add(job.outputs.ambient)
      .add(job.outputs.tonemap)
      .add(job.outputs.exposure);
  f.add(job.outputs.false_colour)
      .add(job.outputs.false_colour_scale.max)
      .add(job.outputs.false_colour_scale.log_decades);
  f.add(job.outputs.image_width).add(job.outputs.image_height).add(job.outputs.camera.has_value());
  if (job.outputs.camera) f.add(*job.outputs.camera);
  f.add(std::string_view(job.outputs.mesh)).add(uint64_t(job.outputs.images.size()));
  for (const std::string& i : job.outputs.images) f.add(std::string_view(i));
  return f.value();
}

namespace {

using Say = std::function<void(const std::string&)>;

// Every file the job writes, refused before any work if it cannot be written.
void check_job_outputs(const SceneJob& job) {
  check_outputs(job.outputs);
  if (!job.stats_json.empty()) check_writable(job.stats_json);
  if (!job.checkpoint.empty()) check_writable(job.checkpoint);
}

// rad batch: the stats file carries this job's fingerprint (written last) and every output is
// there, so an earlier run did this job.
bool done_before(const SceneJob& job, uint64_t job_id) {
  if (!job.skip_if_done || job_id == 0 || read_job_fingerprint(job.stats_json) != job_id) {
    return false;
  }
  bool complete = job.outputs.mesh.empty() || std::filesystem::exists(job.outputs.mesh);
  for (const std::string& image : job.outputs.images) complete &= std::filesystem::exists(image);
  return complete;
}

// Under MPI rank 0 takes every rank's polygons and counters: its state is then the whole
// solve's, as one process would have it. Returns the ranks' reports (empty without MPI and on
// the other ranks). Collective.
std::vector<RankReport> gather_ranks(SolverState& state, Ranks* ranks) {
  if (!ranks) return {};
  std::vector<RankReport> reports = collect(state);
  if (ranks->rank() == 0) {
    state.stats = total_stats(reports);
    state.energy.absorbed_energy = total_absorbed(reports);
  }
  return reports;
}

// The mesh only grows by subdivision, down to --min-size: refuses a solve that could outgrow
// the memory (`growth`: the whole scene's bound, which rank 0 holds at the end) before spending
// any time on it, and returns the limit at which the solve stops. Under MPI the machine's
// memory is shared by its ranks.
size_t check_memory(SolverState& state, double growth, const SceneJob& job, bool under_mpi,
                    const Say& say) {
  const size_t limit = solve_memory_limit(job.max_memory, under_mpi);
  const double now = double(resident_bytes());
  double per_shot = 0.0;
  for (size_t c = 0; c < state.scene.clusters.size(); ++c)
    per_shot = std::max(per_shot, shot_log_bytes(state, c));
  if (limit > 0 && now + growth > double(limit)) {
    throw Error(SourceLoc{job.input.path},
                fmt::format("this solve could need {} ({} now, {} more if every element were "
                            "split down to the smallest size, {:.3g}), over the limit of {}{}; "
                            "raise --min-size, or give --max-memory to run anyway (the solve then "
                            "stops at that limit and writes what it has)",
                            format_bytes(now + growth), format_bytes(now), format_bytes(growth),
                            state.scene.min_size, format_bytes(double(limit)),
                            job.max_memory > 0 ? " (--max-memory)" : " (90% of this machine's)"));
  }
  limit_kept_answers(state.options, limit);
  say(fmt::format(
      "Memory: {} now, at most {} more by subdivision, {} per major shot logged and {} of "
      "kept shadow-ray answers (limit {})",
      format_bytes(now), format_bytes(growth), format_bytes(per_shot),
      format_bytes(double(state.options.kept_rays_bytes)), format_bytes(double(limit))));
  return limit;
}

// --checkpoint: the solver state saved every `every` seconds of its own clock and at the end.
// Under MPI rank 0 writes the whole state (the same file one process writes, so either resumes
// it), gathered from the ranks; between shots it then goes back to its own share.
class Checkpointer {
 public:
  Checkpointer(const SceneJob& job, uint64_t fingerprint, Ranks* ranks)
      : path_(job.checkpoint),
        every_(job.checkpoint_every),
        fingerprint_(fingerprint),
        ranks_(ranks) {}

  void resume(SolverState& state, const Say& say) const {
    if (path_.empty()) return;
    remove_stale_temporaries(path_);
    if (!std::filesystem::exists(path_)) return;
    read_checkpoint(path_, state, fingerprint_);
    say(fmt::format("Resuming from checkpoint {} ({} shots done)", path_, state.shots.count));
  }

  // After each shot: saves when rank 0's clock says it is time (every rank asks it).
  void after_shot(SolverState& state) {
    if (path_.empty()) return;
    bool due = since(saved_) >= every_;
    if (ranks_) due = ranks_->max(due && lead()) > 0;
    if (!due) return;
    if (ranks_) {
      // Each rank goes on counting its own share; rank 0 saves the totals.
      const SolverStats own = state.stats;
      const double absorbed = state.energy.absorbed_energy;
      gather_ranks(state, ranks_);
      if (lead()) write_checkpoint(path_, state, fingerprint_), release_foreign(state);
      state.stats = own, state.energy.absorbed_energy = absorbed;
    } else {
      write_checkpoint(path_, state, fingerprint_);
    }
    saved_ = Clock::now();
  }

  // At the end: rank 0's state made whole and saved. Returns the ranks' reports.
  std::vector<RankReport> finish(SolverState& state) const {
    std::vector<RankReport> reports = gather_ranks(state, ranks_);
    if (!path_.empty() && lead()) write_checkpoint(path_, state, fingerprint_);
    return reports;
  }

 private:
  bool lead() const { return !ranks_ || ranks_->rank() == 0; }

  std::string path_;
  double every_;
  uint64_t fingerprint_;
  Ranks* ranks_;
  Clock::time_point saved_ = Clock::now();
};

// Shots as a progress bar: how far the unshot energy has come down to --converge, on a log
// scale (each shot takes off about a fixed fraction).
void show_progress(Progress& progress, const SolverState& s, const ShotRecord& r, double converge) {
  const double log_goal = std::log(std::max(converge, 1e-12));
  const double f = r.unshot_fraction > 0 ? std::log(r.unshot_fraction) / log_goal : 1.0;
  progress.update(f, fmt::format("shot {}  unshot {:.2e}  subdivisions {}", r.shot,
                                 r.unshot_fraction, s.stats.subdivisions));
}

void say_why_stopped(StopReason stop, size_t memory_limit, const SceneJob& job, const Say& say) {
  if (stop == StopReason::MemoryLimit) {
    say(fmt::format("Stopped at the memory limit ({}): writing the solution so far",
                    format_bytes(double(memory_limit))));
  }
  if (stop == StopReason::Interrupted) {
    say(fmt::format("Stopped by signal {}: writing the solution so far{}", interrupt_signal(),
                    job.checkpoint.empty() ? "" : " (resume with the same command)"));
  }
}

// Stages go to stdout as the original printed them (the progress bar lives on stderr).
Say stage_printer(bool quiet) {
  return [quiet](const std::string& s) {
    if (quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
}

// The solve, shown as it goes and saved when due, until it converges or meets a limit: the
// shots, the time, a signal, or the memory.
StopReason solve_job(SolverState& state, const PreparedSolve& prepared, const RunOptions& run,
                     Checkpointer& checkpoints, Progress& progress, size_t memory_limit) {
  install_interrupt_handlers();
  return solve(
      state, prepared.visibility(),
      [&](const SolverState& s, const ShotRecord& r) {
        show_progress(progress, s, r, run.solver.converge);
        checkpoints.after_shot(state);
      },
      [&]() -> std::optional<StopReason> {
        if (interrupt_signal()) return StopReason::Interrupted;
        if (memory_limit > 0 && resident_bytes() > memory_limit) return StopReason::MemoryLimit;
        return std::nullopt;
      });
}

// Each light group's images beside the whole solve's (group_image_paths), through its camera
// and with its exposure, so that the groups' linear images add up to the whole's. Adds the
// groups' final gathers to times.render.
void write_group_images(const OutputOptions& whole, const SolverState& state,
                        const VisibilityBackend& vis, const ToneMap& tone, const Camera& camera,
                        bool quiet, RunTimes& times, const Say& say, StagedFiles& files) {
  const std::vector<std::string> names = light_groups_kept(*state.solution.hierarchy);
  std::vector<std::vector<std::string>> paths;
  for (const std::string& image : whole.images) paths.push_back(group_image_paths(image, names));
  SolverState view = group_view(state);
  for (size_t g = 0; g < state.solution.group_count; ++g) {
    show_group(view, state, g);
    OutputOptions o = whole;
    o.mesh.clear();
    o.camera = camera;
    o.images.clear();
    for (const std::vector<std::string>& p : paths) o.images.push_back(p[g]);
    say(fmt::format("Light group \"{}\" alone:", names[g]));
    double seconds = 0.0;
    const SolvedScene solved{view, vis, quiet, &seconds};
    write_outputs(make_output_mesh(view, o.ambient), o, tone, say, files, &solved);
    times.render += seconds;
  }
}

// The mesh, the images and the statistics (last: rad batch takes a stats file with this job's
// fingerprint to mean every output is there), all or none. Sets times.write and times.total.
void write_job_outputs(const RunOptions& run, const SceneJob& job, const SolverState& state,
                       const VisibilityBackend& vis, StopReason stop, uint64_t job_id,
                       const std::vector<RankReport>& reports, Clock::time_point start,
                       RunTimes& times, const Say& say) {
  const auto t = Clock::now();
  const OutputMesh mesh = make_output_mesh(state, job.outputs.ambient);
  StagedFiles files;
  const SolvedScene solved{state, vis, run.quiet, &times.render};
  const ToneMap tone =
      scene_tone_map(state, mesh.display, job.outputs.tonemap, job.outputs.exposure);
  const std::optional<Camera> camera = write_outputs(mesh, job.outputs, tone, say, files, &solved);
  if (job.outputs.group_images && camera && state.solution.group_count > 0)
    write_group_images(job.outputs, state, vis, tone, *camera, run.quiet, times, say, files);
  times.write = since(t);
  times.total = since(start);
  if (!job.stats_json.empty()) {
    files.write(job.stats_json, [&](const std::string& path) {
      write_stats_json(path, run, job, state, stop, times,
                       measure_seams(mesh, state.solution.hierarchy->triangles), camera, job_id,
                       reports);
    });
  }
  files.commit();
}

}  // namespace

SceneJobResult run_scene_job(const RunOptions& run, const SceneJob& asked, Ranks* ranks) {
  const auto start = Clock::now();
  SceneJob job = asked;  // a staged model's camera is known once it is read
  // Under MPI rank 0 speaks and writes; the others solve their share quietly.
  const bool lead = !ranks || ranks->rank() == 0;
  const bool quiet = run.quiet || !lead;
  Progress progress(quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
  const Say say = stage_printer(quiet);
  RunTimes times;
  if (lead) check_job_outputs(job);  // rank 0 alone writes, on its own machine
  check_scene_input(job.input);
  if (is_original_output_name(job.outputs.mesh)) {
    say(job.outputs.mesh + ": .gfo is the original's output name; writing Geomview COFF there");
  }

  say(is_model_file(job.input.path) ? "Reading model file..." : "Reading description file...");
  const Hierarchy hierarchy = load_scene(job.input);
  require_light(hierarchy, job.input, run.solver);
  if (hierarchy.model && hierarchy.model->stage) {
    const Stage& stage = *hierarchy.model->stage;
    say(describe_stage(stage, metres_per_unit(job.input)));
    if (!job.outputs.camera) {
      job.outputs.camera =
          stage_camera(stage, float(job.outputs.image_width) / float(job.outputs.image_height));
    }
  }
  times.parse = since(start);
  const uint64_t job_id = job.stats_json.empty() ? 0 : job_fingerprint(run, job, hierarchy);
  if (done_before(job, job_id)) {
    say("Outputs complete from an earlier run with the same scene and options: skipped");
    return {.seconds = since(start), .skipped = true};
  }

  say("Initializing...");
  auto t = Clock::now();
  const PreparedSolve prepared(hierarchy, run);
  SolverOptions solver = run.solver;
  solver.log_minor_shots = false;  // no edits here: the log keeps the major shots only
  SolverState state = make_solver_state(hierarchy, solver);
  const uint64_t fingerprint =
      job.checkpoint.empty() && !ranks ? 0 : solve_fingerprint(hierarchy, run.solver, run.backend);
  Checkpointer checkpoints(job, fingerprint, ranks);
  checkpoints.resume(state, say);
  const double growth = worst_case_growth_bytes(state);  // the whole scene's, before sharing it
  if (ranks) distribute(state, *ranks, fingerprint ^ uint64_t(ranks->size()));
  times.build = since(t);
  const size_t memory_limit = check_memory(state, growth, job, ranks != nullptr, say);

  say(fmt::format(
      "Starting Computation ({} triangles, {} backend, {} thread{}{}{})",
      hierarchy.triangles.size(), to_string(run.backend), prepared.threads(),
      prepared.threads() == 1 ? "" : "s",
      ranks ? fmt::format(" on each of {} MPI ranks", ranks->size()) : "",
      state.solution.group_count > 0
          ? fmt::format(", {} light groups kept apart, no overshooting", state.solution.group_count)
          : ""));
  t = Clock::now();
  const StopReason stop = solve_job(state, prepared, run, checkpoints, progress, memory_limit);
  times.solve = since(t);
  t = Clock::now();
  const std::vector<RankReport> reports = checkpoints.finish(state);
  if (!lead) return {stop, state.shots.count, 0, state.energy.unshot_fraction(), since(start)};
  times.gather = ranks ? since(t) : 0.0;
  progress.finish(fmt::format("{} after {} shots", to_string(stop), state.shots.count));
  say_why_stopped(stop, memory_limit, job, say);

  if (job.outputs.group_images && state.solution.group_count == 0) {
    warn(SourceLoc{job.input.path},
         "--group-images: the scene has no two light groups, so no image more is written; put "
         "emitters in groups with Group \"name\" (descriptions) or --light-group PATTERN=NAME "
         "(models)");
  }
  write_job_outputs(run, job, state, prepared.visibility(), stop, job_id, reports, start, times,
                    say);
  if (!quiet) std::fputs(format_statistics(state, times.total).c_str(), stdout);
  // A scene lit by lights has its light in lux: what a lighting designer looks at first.
  if (!quiet && !state.solution.hierarchy->lights.empty())
    std::fputs(
        format_illuminance(object_illuminance(state, metres_per_unit(job.input)), 12).c_str(),
        stdout);
  return {stop, state.shots.count, count_vertices(state.solution.mesh),
          state.energy.unshot_fraction(), times.total};
}

}  // namespace rad
