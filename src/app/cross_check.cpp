#include "app/cross_check.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "run/prepared_solve.h"
#include "run/scene_checks.h"
#include "run/scene_unit.h"
#include "scene/scene_file.h"
#include "solver/solver.h"
#include "visibility/agreement.h"

namespace rad {

namespace {

// Brute force costs one test per triangle per segment: as many segments as keep it near 2e9
// tests, between 1,000 and 100,000.
size_t segment_count(const Hierarchy& h) {
  return std::clamp<size_t>(size_t(2e9 / double(std::max<size_t>(h.triangles.size(), 1))), 1000,
                            100000);
}

std::string describe(const Segment& s) {
  const Vec3 q = s.origin + s.direction;
  return fmt::format("({:.9g}, {:.9g}, {:.9g}) -> ({:.9g}, {:.9g}, {:.9g})", s.origin.x, s.origin.y,
                     s.origin.z, q.x, q.y, q.z);
}

// Prints the ray-level report of one backend; returns whether it agrees (no mismatch beyond
// rounding distance).
bool report_rays(const Hierarchy& h, BackendKind kind, const VisibilityBackend& oracle,
                 const std::vector<Segment>& segments) {
  const auto backend = make_visibility_backend(kind, h);
  const RayAgreement a = compare_rays(h, oracle, *backend, segments);
  std::printf(
      "  rays, %s against brute force: %zu segments (%zu blocked), %zu differ: %zu within "
      "%.3g of an edge or plane (rounding), %zu farther\n",
      to_string(kind), a.segments, a.blocked, a.mismatches.size(), a.near, ambiguity_limit(h),
      a.far);
  size_t shown_near = 0;
  for (const RayMismatch& m : a.mismatches) {
    const bool far = m.ambiguity >= ambiguity_limit(h);
    if (!far && shown_near++ >= 10) continue;
    std::printf("    %s %s: brute force %s, %s %s (%.3g from an edge or plane)\n",
                far ? "MISMATCH" : "rounding", describe(m.segment).c_str(),
                m.expected ? "blocked" : "clear", to_string(kind), m.got ? "blocked" : "clear",
                m.ambiguity);
  }
  if (shown_near > 10) std::printf("    ... and %zu more within rounding\n", shown_near - 10);
  return a.far == 0;
}

// Answers with `primary` and asks `secondary` the same: the rays a solve really casts, each one
// the two answer differently recorded (per thread, no locks). A diagnostic, so it may be slow.
class ComparingBackend final : public VisibilityBackend {
 public:
  ComparingBackend(const VisibilityBackend& primary, const VisibilityBackend& secondary)
      : primary_(primary), secondary_(secondary) {}
  BackendKind kind() const override { return primary_.kind(); }
  void occluded(std::span<const Segment> segments, std::span<uint8_t> out,
                VisibilityStats& stats) const override {
    primary_.occluded(segments, out, stats);
    Local& local = local_.local();
    local.answers.resize(segments.size());
    VisibilityStats ignored;
    secondary_.occluded(segments, local.answers, ignored);
    local.compared += segments.size();
    for (size_t i = 0; i < segments.size(); ++i) {
      if (out[i] != local.answers[i]) {
        local.mismatches.push_back({segments[i], out[i], local.answers[i], 0.0});
      }
    }
  }
  // The fan path of the base class makes segments and calls occluded(): both see the same rays.
  SegmentHit first_hit(const Segment& segment, VisibilityStats& stats) const override {
    const SegmentHit a = primary_.first_hit(segment, stats);
    VisibilityStats ignored;
    const SegmentHit b = secondary_.first_hit(segment, ignored);
    Local& local = local_.local();
    ++local.compared;
    if (a.hit != b.hit || a.t != b.t || a.normal != b.normal) {
      local.mismatches.push_back({segment, uint8_t(a.hit), uint8_t(b.hit), 0.0});
    }
    return a;
  }

  size_t compared() const {
    size_t n = 0;
    for (const Local& l : local_) n += l.compared;
    return n;
  }
  std::vector<RayMismatch> mismatches() const {
    std::vector<RayMismatch> all;
    for (const Local& l : local_) all.insert(all.end(), l.mismatches.begin(), l.mismatches.end());
    return all;
  }

 private:
  struct Local {
    std::vector<uint8_t> answers;
    std::vector<RayMismatch> mismatches;
    size_t compared = 0;
  };
  const VisibilityBackend& primary_;
  const VisibilityBackend& secondary_;
  mutable tbb::enumerable_thread_specific<Local> local_;
};

}  // namespace

int run_cross_check(const CommandLine& cmd) {
  const BackendKind first = cmd.run.backend, second = *cmd.cross_check;
  const SceneInput& in = cmd.job.input;
  check_scene_input(in);
  const Hierarchy h = load_scene(in);
  require_light(h, in, cmd.run.solver);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            size_t(thread_count(cmd.run.threads)));
  std::printf("Cross-check of %s: %s against %s (%zu triangles)\n", in.path.c_str(),
              to_string(first), to_string(second), h.triangles.size());

  const auto brute = make_visibility_backend(BackendKind::Brute, h);
  const std::vector<Segment> segments = random_segments(h, segment_count(h), 20261201);
  bool agree = true;
  for (BackendKind k : {first, second}) {
    if (k != BackendKind::Brute) agree &= report_rays(h, k, *brute, segments);
  }

  // The first solve asks both backends every ray it casts and goes by the first one's answers.
  SolverState a = make_solver_state(h, cmd.run.solver), b = make_solver_state(h, cmd.run.solver);
  const auto vis_a = make_visibility_backend(first, h), vis_b = make_visibility_backend(second, h);
  const ComparingBackend both(*vis_a, *vis_b);
  const StopReason stop_a = solve(a, both);
  const StopReason stop_b = solve(b, *vis_b);
  std::vector<RayMismatch> cast = both.mismatches();
  size_t cast_near = 0;
  for (RayMismatch& m : cast) {
    m.ambiguity = ambiguity_distance(h, m.segment);
    cast_near += m.ambiguity < ambiguity_limit(h);
  }
  std::sort(cast.begin(), cast.end(),
            [](const RayMismatch& x, const RayMismatch& y) { return x.ambiguity > y.ambiguity; });
  std::printf(
      "  rays the %s solve cast: %zu, answered differently by %s: %zu (%zu within %.3g "
      "of an edge or plane, %zu farther)\n",
      to_string(first), both.compared(), to_string(second), cast.size(), cast_near,
      ambiguity_limit(h), cast.size() - cast_near);
  for (size_t i = 0; i < cast.size() && i < 20; ++i) {
    std::printf("    %s: %s %s, %s %s (%.3g from an edge or plane)\n",
                describe(cast[i].segment).c_str(), to_string(first),
                cast[i].expected ? "blocked" : "clear", to_string(second),
                cast[i].got ? "blocked" : "clear", cast[i].ambiguity);
  }
  if (cast.size() > 20) std::printf("    ... and %zu more\n", cast.size() - 20);
  std::printf("  solves: %s %lld shots (%s), %s %lld shots (%s)\n", to_string(first),
              static_cast<long long>(a.shots.count), to_string(stop_a), to_string(second),
              static_cast<long long>(b.shots.count), to_string(stop_b));
  size_t differing = 0, compared = 0;
  int64_t first_differing = -1;
  float largest = 0.0f, worst = 0.0f;
  Vec3 worst_at(0.0f);
  for (size_t p = 0; p < a.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh &pa = a.solution.mesh.polygons[p], &pb = b.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < pa.vertex_count(); ++v)
      largest = std::max(largest, max_component(a.solution.radiosity(p, v)));
    if (pa.vertex_count() != pb.vertex_count() || pa.elements.size() != pb.elements.size()) {
      if (differing++ == 0) first_differing = int64_t(p);
      continue;
    }
    for (uint32_t v = 0; v < pa.vertex_count(); ++v) {
      ++compared;
      const float d =
          max_component(glm::abs(a.solution.radiosity(p, v) - b.solution.radiosity(p, v)));
      if (d > worst) worst = d, worst_at = pa.positions[v];
    }
  }
  const float relative = largest > 0.0f ? worst / largest : 0.0f;
  std::printf("  vertices: %s %zu, %s %zu; %zu polygons subdivided differently", to_string(first),
              count_vertices(a.solution.mesh), to_string(second), count_vertices(b.solution.mesh),
              differing);
  if (first_differing >= 0) {
    const SceneObject& o = h.objects[size_t(h.triangles.object[size_t(first_differing)])];
    std::printf(" (the first: triangle %lld of \"%s\", %s)",
                static_cast<long long>(first_differing), o.name.c_str(), to_string(o.loc).c_str());
  }
  std::printf(
      "\n  radiosity over the %zu vertices in both: largest difference %.3g of the largest "
      "radiosity, at (%.6g, %.6g, %.6g)\n",
      compared, relative, worst_at.x, worst_at.y, worst_at.z);
  agree &= differing == 0 && relative <= 1e-5f && a.shots.count == b.shots.count;
  std::printf("%s\n", agree ? "agree"
                            : "DISAGREE (rays beyond rounding, subdivision, or radiosity "
                              "beyond 1e-5 of the largest)");
  return agree ? 0 : 1;
}

}  // namespace rad
