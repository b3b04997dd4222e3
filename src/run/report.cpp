#include "run/report.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <tbb/info.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "mesh/patch_mesh.h"
#include "run/object_illuminance.h"
#include "run/prepared_solve.h"
#include "run/scene_unit.h"

namespace rad {

namespace {
double percent(uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; }
}  // namespace

std::string format_statistics(const SolverState& s, double elapsed) {
  const VisibilityStats& r = s.stats.rays;
  std::string o = "Ray-Tracing Statistics:\n";
  o += fmt::format("Number of rays shot:          {}\n", r.rays);
  o += fmt::format("Number of hits on polygons:   {} ({:.2f}%)\n", r.occluded,
                   percent(r.occluded, r.rays));
  o += fmt::format("Number of trials on bounding boxes: {}\n", r.box_trials);
  o += fmt::format("Number of hits on bounding boxes: {} ({:.2f}%)\n", r.box_hits,
                   percent(r.box_hits, r.box_trials));
  o += fmt::format("Number of intensity cuts:    {}\n", s.stats.intensity_cuts);
  o += fmt::format("Shadow-ray answers kept:     {} ({:.2f}% of those needed)\n",
                   s.stats.kept_answers,
                   percent(s.stats.kept_answers, s.stats.kept_answers + r.rays));
  o += fmt::format("Shots: {}, subdivisions: {}, vertices: {}, elements: {}\n", s.shots.count,
                   s.stats.subdivisions, count_vertices(s.solution.mesh),
                   count_leaves(s.solution.mesh));
  o += fmt::format("Unshot energy left: {:.3g} of emitted\n", s.energy.unshot_fraction());
  o += fmt::format("Total elapsed time is {:.2f} seconds\n", elapsed);
  return o;
}

const char* rad_version() { return RAD_VERSION; }

size_t peak_memory_bytes() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return size_t(u.ru_maxrss) * 1024;
}

void write_stats_json(const std::string& path, const RunOptions& run, const SceneJob& job,
                      const SolverState& s, StopReason stop, const RunTimes& t,
                      const SeamReport& seams, const std::optional<Camera>& camera,
                      uint64_t job_fingerprint, const std::vector<RankReport>& ranks) {
  using nlohmann::json;
  const VisibilityStats& r = s.stats.rays;
  const Vec3 ambient = ambient_radiosity(s.energy, s.solution);
  // Energies are radiosity times area in square scene units: square metres with --unit.
  const double unit = metres_per_unit(job.input), square_metres = unit * unit;
  json history = json::array();
  for (const ShotRecord& h : s.shots.history) {
    history.push_back({{"shot", h.shot},
                       {"source", h.source},
                       {"seconds", h.seconds},
                       {"unshot_fraction", h.unshot_fraction}});
  }
  json j = {
      {"schema", "rad-stats"},
      {"version", 1},
      {"rad_version", rad_version()},
      {"scene",
       {{"path", job.input.path},
        {"name", s.solution.hierarchy->scene_name},
        {"triangles", s.solution.hierarchy->triangles.size()}}},
      {"backend", to_string(run.backend)},
      {"packets", run.packets},
      {"threads", thread_count(run.threads)},
      {"options",
       {{"shadows", s.options.shadows},
        {"samples", s.options.sample_grid * s.options.sample_grid},
        {"max_samples", std::max(s.options.sample_grid, s.options.max_sample_grid) *
                            std::max(s.options.sample_grid, s.options.max_sample_grid)},
        {"clusters", s.scene.clusters.size()},
        {"form_factor", s.options.method == FormFactorMethod::Analytic ? "analytic" : "samples"},
        {"threshold", s.options.subdivision_threshold},
        {"intensity_cut", s.options.intensity_cut},
        {"roulette", s.options.roulette},
        {"overshoot", s.options.overshoot},  // off with light groups, whatever was asked
        {"converge", s.options.converge},
        {"min_size", s.scene.min_size},
        {"unit", unit}}},
      {"stop_reason", to_string(stop)},
      {"partial", stop == StopReason::Interrupted || stop == StopReason::MemoryLimit},
      {"checkpoint",
       job.checkpoint.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.checkpoint)},
      {"rays",
       {{"shot", r.rays},
        {"hits_on_polygons", r.occluded},
        {"box_trials", r.box_trials},
        {"box_hits", r.box_hits},
        {"cells_visited", r.cells_visited},
        {"triangle_tests", r.triangle_tests},
        {"intensity_cuts", s.stats.intensity_cuts},
        {"kept_answers", s.stats.kept_answers},
        {"kept_answer_bytes", s.kept.bytes}}},
      {"solver",
       {{"shots", s.shots.count},
        {"subdivisions", s.stats.subdivisions},
        {"exact_midpoints", s.stats.exact_midpoints},
        {"interpolated_midpoints", s.stats.interpolated_midpoints},
        {"vertex_evaluations", s.stats.vertex_evaluations},
        {"middles_gathered", s.stats.middles},
        {"culled", s.stats.culled},
        {"roulette_skipped", s.stats.roulette},
        {"hidden_triangles", s.stats.hidden},
        {"vertices", count_vertices(s.solution.mesh)},
        {"elements", count_leaves(s.solution.mesh)},
        {"emitted_energy", s.energy.emitted_energy * square_metres},
        {"absorbed_energy", s.energy.absorbed_energy * square_metres},
        {"unshot_fraction", s.energy.unshot_fraction()},
        {"ambient", {ambient.x, ambient.y, ambient.z}},
        {"ambient_displayed", job.outputs.ambient}}},
      {"seconds",
       {{"parse", t.parse},
        {"build", t.build},
        {"solve", t.solve},
        {"shoot", s.stats.shoot_seconds},
        {"refine", s.stats.refine_seconds},
        {"write", t.write},
        {"render", t.render},
        {"total", t.total}}},
      {"seams",
       {{"shared_edges", seams.shared_edges},
        {"vertices_checked", seams.vertices_checked},
        {"largest_jump", seams.largest_jump},
        {"mean_jump", seams.mean_jump},
        {"mean_radiosity", seams.mean_radiosity},
        {"largest_jump_at", {seams.where.x, seams.where.y, seams.where.z}}}},
      {"peak_memory_bytes", peak_memory_bytes()},
      {"history", history},
  };
  if (!ranks.empty()) {
    // Per MPI rank: its share, its time, and the time it spent communicating (waiting for the
    // slowest rank included) and the bytes it broadcast as the owner of a shooter.
    json per_rank = json::array();
    uint64_t bytes = 0, broadcasts = 0;
    for (size_t i = 0; i < ranks.size(); ++i) {
      const RankReport& k = ranks[i];
      bytes += k.broadcast_bytes, broadcasts += k.broadcasts;
      per_rank.push_back({{"rank", i},
                          {"vertices", k.vertices},
                          {"rays", k.stats.rays.rays},
                          {"shoot_seconds", k.stats.shoot_seconds},
                          {"refine_seconds", k.stats.refine_seconds},
                          {"communication_seconds", k.communication_seconds},
                          {"broadcast_bytes", k.broadcast_bytes}});
    }
    j["mpi"] = {{"ranks", ranks.size()},
                {"gather_seconds", t.gather},
                {"shot_source_bytes_mean", broadcasts ? double(bytes) / double(broadcasts) : 0.0},
                {"per_rank", per_rank}};
  }
  // Per object: the light arriving (lux with photometric lights), least, mean, most.
  json objects = json::array();
  for (const ObjectIlluminance& o : object_illuminance(s, unit)) {
    objects.push_back({{"name", o.name},
                       {"area", o.area},
                       {"illuminance", {{"min", o.min}, {"mean", o.mean}, {"max", o.max}}}});
  }
  j["objects"] = objects;
  if (s.solution.group_count > 0) {
    // The light groups' names, in the order of the outputs' group properties.
    j["light_groups"] = light_groups_kept(*s.solution.hierarchy);
  }
  j["lights"] = s.solution.hierarchy->lights.size();
  // Each light's power (lumens with candela or lux in metres) as the solve counts it.
  json light_power = json::array();
  const std::vector<Light>& lights = s.solution.hierarchy->lights;
  for (size_t i = 0; i < lights.size() && i < s.energy.light_power.size(); ++i) {
    const Vec3& c = lights[i].colour;
    light_power.push_back(
        {{"name", lights[i].name},
         {"kind", to_string(lights[i].kind)},
         {"lumens", s.energy.light_power[i] * (c.x + c.y + c.z) / 3.0 * square_metres}});
  }
  j["light_power"] = light_power;
  // The camera the images were rendered through, as --camera takes it (null: no image).
  j["camera"] = camera ? json(camera_spec(*camera)) : json(nullptr);
  // Hex: JSON numbers are doubles to most readers.
  if (job_fingerprint != 0) j["job_fingerprint"] = fmt::format("{:016x}", job_fingerprint);
  AtomicFile f(path);
  f.stream() << j.dump(2) << "\n";
  f.commit();
}

std::optional<uint64_t> read_job_fingerprint(const std::string& stats_json) {
  std::ifstream in(stats_json);
  if (!in) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("job_fingerprint") || !j["job_fingerprint"].is_string()) {
    return std::nullopt;
  }
  const std::string hex = j["job_fingerprint"].get<std::string>();
  char* end = nullptr;
  const uint64_t v = std::strtoull(hex.c_str(), &end, 16);
  if (hex.empty() || *end != '\0') return std::nullopt;
  return v;
}

}  // namespace rad
