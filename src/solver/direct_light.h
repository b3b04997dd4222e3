// The direct light of the scene's emitters, apart from the light that reaches a point after
// bouncing: what a final gather (export/gathered_image.h) recomputes at each visible point,
// with the same estimator as the solver's shots, while the bounced part is read from the
// solution.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/gather.h"
#include "solver/shot_source.h"
#include "solver/solver_state.h"

namespace rad {

/// Each emitting cluster frozen with its emission (make_emission_source) and each light of the
/// scene, as sources that shoot once; and for each, the shadow-ray ends of `variants` sets:
/// set 0 is the solver's own (each stratum's ray ends where its power is), set k > 0 ends each
/// stratum's ray at one of its fine points drawn by power from k, so that points reading
/// different sets find a penumbra's edge at different points and it has no fixed step.
struct DirectLight {
  std::vector<ShotSource> sources;
  uint32_t variants = 1;
  /// Per source, per set: the ends, x then y then z (3 x the source's ends each).
  std::vector<std::vector<float>> ends;
  /// Per polygon p, the sources that may light it: lit_by[lit_first[p] .. lit_first[p + 1]),
  /// in source order; those it is not hidden from by occlusion culling (occlusion_culling.h:
  /// what every shadow ray to the source would find blocked), so that in a building a point
  /// looks at its own room's lamps, not every lamp. Empty without culling: every source.
  std::vector<uint32_t> lit_first, lit_by;
};

/// The direct light of `s`'s scene: its emitting clusters (any polygon of non-zero emission) in
/// cluster order, then its lights, with `variants` (>= 1) sets of shadow-ray ends.
DirectLight make_direct_light(const SolverState& s, uint32_t variants);

/// What a thread needs to evaluate direct light: its own copy of the sources, whose ends it
/// swaps for the set a point asks for, and the gathering scratch.
struct DirectLightScratch {
  std::vector<ShotSource> sources;
  std::vector<uint32_t> set;  // per source, the set its ends hold now
  GatherScratch gather;
};

/// The direct gain H (radiosity before the receiver's reflectance) that point x with unit
/// normal n on polygon p gets from every source that may light p (may_receive, the Lights
/// lists), its shadow rays ending at set `set` (taken modulo the sets). The solver's gather
/// settings for p (receiver_settings).
Vec3 direct_gain(const SolverState& s, const DirectLight& d, size_t p, const Vec3& x, const Vec3& n,
                 uint32_t set, const VisibilityBackend& vis, const GatherSettings& settings,
                 DirectLightScratch& scratch);

}  // namespace rad
