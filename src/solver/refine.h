// Adaptive subdivision after a shot (SPEC §5).
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

/// Splits, level by level, every leaf of the received polygons whose vertices differ by more
/// than the subdivision limit, until within the limit or at the minimum size. A new midpoint
/// on an edge whose ends differ by more than the limit gets the earlier shots' part
/// interpolated and the current shot's part computed exactly (in parallel over all such
/// vertices); one on an edge within the limit gets the mean of its ends, so an unsplit
/// neighbour sharing that edge shows no discontinuity.
/// The shots of s.shot_log gathered again at point x of `polygon` (all, or the major ones only);
/// the major ones' part is also written to *major_part when given.
Vec3 regather_shots(const SolverState& s, const Vec3& x, uint32_t polygon, bool major_only,
                    const VisibilityBackend& vis, const GatherSettings& settings,
                    GatherScratch& scratch, Vec3* major_part);

/// The refinement; with src == nullptr it runs between shots (after an edit changed the
/// polygons' radiosity): every new vertex gathers every logged shot again, so H is exact, and
/// its unshot radiosity takes the edit's part d_rho * H exactly.
void refine_polygons(SolverState& s, const ShotSource* src, bool major, const Vec3& d_rho,
                     const VisibilityBackend& vis, std::span<const uint32_t> polygons);

/// A new exact vertex also gathers every major shot of s.shot_log again, so only the minor shots'
/// part is interpolated; `major` says whether the current shot is one.
/// The polygons refined are the shot's receivers (s.receivers).
void refine_after_shot(SolverState& s, const ShotSource& src, const VisibilityBackend& vis,
                       bool major);

}  // namespace rad
