// Adaptive subdivision (design §5): after a shot, and after an edit.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "solver/gather.h"
#include "solver/shot_source.h"

namespace rad {

/// True when the radiosities of two vertices differ by more than `limit` in some channel.
inline bool differs(const Vec3& a, const Vec3& b, float limit) {
  return max_component(glm::abs(a - b)) > limit;
}

/// Whether a leaf of polygon p is to be split: its vertices' radiosities differ by more than the
/// subdivision limit and it is still twice the minimum size. A polygon without one is left as it
/// is by both refinements.
bool needs_refinement(const SolverState& s, uint32_t p);

/// Those of `polygons` that needs_refinement names, in order.
std::vector<uint32_t> needing_refinement(const SolverState& s, std::span<const uint32_t> polygons);

/// The shots of s.shots.sources gathered again at point x of `polygon` (all, or the major ones
/// only); the major ones' part is also written to *major_part when given.
Vec3 regather_shots(const SolverState& s, const Vec3& x, uint32_t polygon, bool major_only,
                    const VisibilityBackend& vis, const GatherSettings& settings,
                    GatherScratch& scratch, Vec3* major_part);

/// Both refinements split, level by level, every leaf of their polygons whose vertices differ by
/// more than the subdivision limit, until within the limit or at the minimum size.
///
/// After a shot, over `polygons`: its receivers, or only those of them that needs_refinement
/// names, the others being left as they are (the solver looks at each receiver once for this and
/// for its bookkeeping); a midpoint shared with a polygon the shot reached (s.receivers.marked)
/// copies its gain. Writes the polygons' meshes and vertex states, s.scene.shared and
/// s.scene.buried (for the new vertices) and s.stats. A new midpoint on
/// an edge whose ends differ by more than the limit (every one with MidpointRule::Exact) gathers
/// the shot and every major shot of s.shots.sources again, so only the minor shots' part is
/// interpolated; one on an edge within the limit gets the mean of its ends, so an unsplit neighbour
/// sharing that edge shows no discontinuity. `major` says whether the current shot is one.
void refine_after_shot(SolverState& s, const ShotSource& src, const VisibilityBackend& vis,
                       bool major, std::span<const uint32_t> polygons);

/// The refinement between shots, after an edit changed `polygons`' radiosity: every new
/// vertex gathers every logged shot again, so H is exact, and its unshot radiosity takes the
/// edit's part d_rho * H exactly.
void refine_after_edit(SolverState& s, const Vec3& d_rho, const VisibilityBackend& vis,
                       std::span<const uint32_t> polygons);

}  // namespace rad
