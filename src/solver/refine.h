// Adaptive subdivision (design §5): after a shot, and after an edit.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/gather.h"
#include "solver/shot_source.h"
#include "solver/solver_state.h"

namespace rad {

/// True when the radiosities of two vertices differ by more than `limit` in some channel.
inline bool differs(const Vec3& a, const Vec3& b, float limit) {
  return max_component(glm::abs(a - b)) > limit;
}

/// How far two vertices' radiosities may differ before their element splits: the options'
/// threshold in units of the energy's radiosity scale.
inline float subdivision_limit(const SolverOptions& options, const EnergyBalance& energy) {
  return options.subdivision_threshold * energy.radiosity_scale;
}

/// Whether a leaf of polygon p is to be split: its vertices' radiosities differ by more than the
/// subdivision limit (the options' threshold in units of the energy's radiosity scale), or it
/// crosses into a solid (scene.buried), and it is still twice the minimum size; after a
/// `major_shot` with exact midpoints, also when it holds the shot's shadow edge (refine.cpp);
/// or it is among `bright_middles` (the shot's list for p: Receivers::bright_middles_of). A
/// polygon without one is left as it is by both refinements.
bool needs_refinement(const SolverOptions& options, const EnergyBalance& energy,
                      const SceneCaches& scene, const Solution& sol, uint32_t p,
                      bool major_shot = false, std::span<const LeafRef> bright_middles = {});

/// Those of `polygons` that needs_refinement names, in order.
std::vector<uint32_t> needing_refinement(const SolverOptions& options, const EnergyBalance& energy,
                                         const SceneCaches& scene, const Solution& sol,
                                         std::span<const uint32_t> polygons);

/// The shots of shots.sources gathered again at point x of `polygon` of `h` (all, or the major
/// ones only; those that may_receive passes over skipped); the major ones' part is also written
/// to *major_part when given. With light groups, `group_all` and `group_major` (each empty, or
/// one per group) get each group's part of the two.
Vec3 regather_shots(const Hierarchy& h, const Clusters& clusters, const ShotLog& shots,
                    const Vec3& x, uint32_t polygon, bool major_only, const VisibilityBackend& vis,
                    const GatherSettings& settings, GatherScratch& scratch, Vec3* major_part,
                    std::span<Vec3> group_all = {}, std::span<Vec3> group_major = {});

/// The parts of the solver state a refinement reads (const) and writes; a view, passed by value.
struct RefineContext {
  const SolverOptions& options;  // the threshold, the midpoint rule, the gather settings
  const EnergyBalance& energy;   // the radiosity scale the limit is in units of
  const ShotLog& shots;          // the logged shots new vertices gather again
  Solution& solution;            // the polygons' meshes, vertex states and texture factors
  SceneCaches& scene;  // read: clusters, sizes; written: the new shared and buried vertices
  SolverStats& stats;
};

/// Both refinements split, level by level, every leaf of their polygons whose vertices differ by
/// more than the subdivision limit, until within the limit or at the minimum size; they write
/// what RefineContext says.
///
/// After a shot, over `polygons`: its receivers, or only those of them that needs_refinement
/// names, the others being left as they are (the solver looks at each receiver once for this and
/// for its bookkeeping); a midpoint shared with a polygon the shot reached (`reached`, as
/// shoot_to_receivers returned it) copies its gain. A new midpoint on an edge whose ends differ by
/// more than the limit (every one with MidpointRule::Exact) gathers the shot and every major shot
/// of ctx.shots again, so only the minor shots' part is interpolated; one on an edge within the
/// limit gets the mean of its ends, so an unsplit neighbour sharing that edge shows no
/// discontinuity. `major` says whether the current shot is one.
void refine_after_shot(RefineContext ctx, const Receivers& reached, const ShotSource& src,
                       const VisibilityBackend& vis, bool major,
                       std::span<const uint32_t> polygons);

/// The refinement between shots, after an edit changed `polygons`' radiosity (over those that
/// needs_refinement names): every new vertex gathers every logged shot again, so H is exact, and
/// its unshot radiosity takes the edit's part d_rho * H exactly.
void refine_after_edit(RefineContext ctx, const Vec3& d_rho, const VisibilityBackend& vis,
                       std::span<const uint32_t> polygons);

}  // namespace rad
