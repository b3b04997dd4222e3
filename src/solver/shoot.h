// One shot of progressive refinement: every receiving vertex gathers from the source.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/gather.h"
#include "solver/shot_source.h"

namespace rad {

/// Gather settings for a state (absolute cut level from the relative option).
GatherSettings gather_settings(const SolverState& s);

/// `g` for receiving polygon p: without shadow rays where its object receives no shadows.
GatherSettings receiver_settings(const GatherSettings& g, const SolverState& s, size_t p);

/// SceneObject::influence of the Pure that shoots `src`: -1 when it lights everything.
int32_t shooter_influence(const SolverState& s, const ShotSource& src);

/// False when no point of polygon p can gain from `src`: p belongs to the planar cluster that
/// shoots, or is not on its Lights list, or lies behind all of it, or all of it lies behind p's
/// plane.
bool may_receive(const SolverState& s, size_t p, const ShotSource& src);

/// Shoots `src` (whose unshot radiosity the caller has already cleared) to every vertex of every
/// other polygon, in parallel over polygons and their vertices (TBB). Each vertex gets
/// H += dH, unshot += rho * dH and last_gain = dH (VertexState::receive; with `major`, dH is
/// also added to its `major` part). Reads s.options, s.scene and s.ownership; writes the
/// receiving vertices' states in s.solution, the kept answers (s.kept) and s.stats; returns the
/// polygons that may have gained (s.receivers, in index order; the others' last_gain is stale),
/// which the rest of the shot takes from the return value.
const Receivers& shoot_to_receivers(SolverState& s, const ShotSource& src,
                                    const VisibilityBackend& vis, bool major);

}  // namespace rad
