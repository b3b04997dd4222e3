// One shot of progressive refinement: every receiving vertex gathers from the source.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/gather.h"
#include "solver/shot_source.h"
#include "solver/solver_state.h"

namespace rad {

/// Gather settings for a solve: the options' methods, their relative cut level made absolute by
/// the energy's scales, and the scene's shadow offset.
GatherSettings gather_settings(const SolverOptions& options, const SceneCaches& scene,
                               const EnergyBalance& energy);

/// The same, read off a whole state, for readers that hold one (the final gather, tests).
inline GatherSettings gather_settings(const SolverState& s) {
  return gather_settings(s.options, s.scene, s.energy);
}

/// `g` for receiving polygon p of `h`: without shadow rays where its object receives no shadows.
GatherSettings receiver_settings(const GatherSettings& g, const Hierarchy& h, size_t p);

/// The same, read off a whole state, for readers that hold one (the final gather).
inline GatherSettings receiver_settings(const GatherSettings& g, const SolverState& s, size_t p) {
  return receiver_settings(g, *s.solution.hierarchy, p);
}

/// SceneObject::influence of the Pure that shoots `src` (a cluster of `clusters`): -1 when it
/// lights everything.
int32_t shooter_influence(const Hierarchy& h, const Clusters& clusters, const ShotSource& src);

/// False when no point of polygon p can gain from `src`: p belongs to the planar cluster that
/// shoots, or is not on its Lights list, or lies behind all of it, or all of it lies behind p's
/// plane.
bool may_receive(const Hierarchy& h, const Clusters& clusters, size_t p, const ShotSource& src);

/// The parts of the solver state a shot reads (const) and writes; a view, passed by value.
struct ShotContext {
  const SolverOptions& options;
  const SceneCaches& scene;     // clusters, shared and buried vertices, culling, shadow offset
  const EnergyBalance& energy;  // the scales of gather_settings
  const ShotLog& shots;         // the shot's number, which the kept answers are stamped with
  const Ownership& ownership;   // under MPI: the polygons this rank receives for
  Solution& solution;           // the receiving vertices' states
  Receivers& receivers;         // the polygons reached, and the loop's work lists
  KeptRayStore& kept;           // the shadow-ray answers kept for the cluster's next shot
  SolverStats& stats;
};

/// Shoots `src` (whose unshot radiosity the caller has already cleared) to every vertex of every
/// other polygon, in parallel over polygons and their vertices (TBB). Each vertex gets
/// H += dH, unshot += rho * dH and last_gain = dH (VertexState::receive; with `major`, dH is
/// also added to its `major` part). Returns the polygons that may have gained (ctx.receivers, in
/// index order; the others' last_gain is stale), which the rest of the shot takes from the
/// return value.
const Receivers& shoot_to_receivers(ShotContext ctx, const ShotSource& src,
                                    const VisibilityBackend& vis, bool major);

}  // namespace rad
