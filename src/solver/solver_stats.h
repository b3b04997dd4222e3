// Counters of a solve, summed over shots.
#pragma once

#include <cstdint>

#include "visibility/backend.h"

namespace rad {

/// Counters of a solve, summed over shots (per-thread during a shot, combined after it).
struct SolverStats {
  VisibilityStats rays;
  uint64_t intensity_cuts = 0;  // shadow rays skipped by the intensity cut (all but one)
  uint64_t kept_answers = 0;    // shadow rays not traced again: answer kept (kept_rays.h)
  uint64_t culled = 0;          // vertex evaluations skipped: source behind or facing away
  uint64_t roulette = 0;        // vertex evaluations skipped by the roulette (shot_source.h)
  /// Receiving triangles a shot skipped whole: hidden by an occluder, behind the source, or
  /// beyond the roulette's reach (when culling is on).
  uint64_t hidden = 0;
  uint64_t vertex_evaluations = 0;  // vertex-to-source gathers computed
  /// Gathers at leaves' middles after major shots, without shadow rays and then, where that
  /// says they may be bright, with them (counted among those above or culled: shoot.cpp).
  uint64_t middles = 0;
  uint64_t subdivisions = 0;     // elements split into four
  uint64_t exact_midpoints = 0;  // new vertices whose shot was computed
  uint64_t interpolated_midpoints = 0;
  double shoot_seconds = 0.0, refine_seconds = 0.0;

  SolverStats& operator+=(const SolverStats& o) {
    rays += o.rays;
    intensity_cuts += o.intensity_cuts;
    kept_answers += o.kept_answers;
    culled += o.culled;
    roulette += o.roulette;
    hidden += o.hidden;
    vertex_evaluations += o.vertex_evaluations;
    middles += o.middles;
    subdivisions += o.subdivisions;
    exact_midpoints += o.exact_midpoints;
    interpolated_midpoints += o.interpolated_midpoints;
    shoot_seconds += o.shoot_seconds;
    refine_seconds += o.refine_seconds;
    return *this;
  }
};

}  // namespace rad
