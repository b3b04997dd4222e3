// Changes between shots that continue the same solve (Chen, "Incremental Radiosity",
// SIGGRAPH 1990; George, Sillion, Greenberg 1990): materials, lights, forced subdivision.
#pragma once

#include <cstdint>

#include "solver/solver_state.h"

namespace rad {

/// Gives Pure `object` a new material and turns the change into unshot radiosity, positive or
/// negative: an emission change dE adds dE to every vertex's unshot radiosity; a reflectance
/// change d(rho) adds d(rho) * H (each vertex keeps its gathered H, so this is exact even from
/// rho = 0). B = E + rho H is current at once; where it now varies beyond the limit (a surface
/// that was black was never subdivided) the object is refined at once, every new vertex
/// gathering every logged shot again. Further steps converge to the new solution.
/// Throws rad::Error if `object` is not a Pure or the material is out of range.
void set_material(SolverState& s, int32_t object, const Material& m, const VisibilityBackend& vis);

/// Splits every leaf of polygon p one level (skipping leaves already at the minimum size).
/// Each new vertex gathers every shot of the log again, so its radiosity is exact, not
/// interpolated. Returns the number of new vertices. Parallel inside.
size_t force_subdivide(SolverState& s, int32_t polygon, const VisibilityBackend& vis);

}  // namespace rad
