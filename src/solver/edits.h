// Changes between shots that continue the same solve (Chen, "Incremental Radiosity",
// SIGGRAPH 1990; George, Sillion, Greenberg 1990): materials, lights, forced subdivision.
#pragma once

#include <cstdint>

#include "solver/solver_state.h"

namespace rad {

/// The parts of the solver state an edit between shots reads (const) and writes; a view, passed
/// by value.
struct EditContext {
  const SolverOptions& options;
  const ShotLog& shots;        // the logged shots the vertices an edit makes gather again
  const Ownership& ownership;  // under MPI: the ranks the unshot totals are summed over
  Solution& solution;          // the materials, the edited polygons' meshes and vertex states
  SceneCaches& scene;          // the buried vertices (found once) and the new vertices among them
  EnergyBalance& energy;       // the unshot and emitted energies
  SolverStats& stats;
};

/// The parts of `s` an edit takes.
inline EditContext edit_context(SolverState& s) {
  return {s.options, s.shots, s.ownership, s.solution, s.scene, s.energy, s.stats};
}

/// Gives Pure `object` a new material and turns the change into unshot radiosity, positive or
/// negative: an emission change dE adds dE to every vertex's unshot radiosity; a reflectance
/// change d(rho) adds d(rho) * H (each vertex keeps its gathered H, so this is exact even from
/// rho = 0). B = E + rho H is current at once; where it now varies beyond the limit (a surface
/// that was black was never subdivided) the object is refined at once, every new vertex
/// gathering every logged shot again. Further steps converge to the new solution.
/// Throws rad::Error if `object` is not a Pure or the material is out of range.
void set_material(EditContext ctx, int32_t object, const Material& m, const VisibilityBackend& vis);

/// Gives light `light` of the scene (Hierarchy::lights) a new colour and intensity (candela, or
/// lux for a directional light, in the hierarchy's units), kept in sol.lights, and turns the
/// change into light it has still to shoot (energy.light_unshot, and the emitted energy
/// convergence is measured against), per channel and of either sign. A light gives colour x
/// intensity x its distribution, linear in both, so the change is a shot of the scene's light
/// whose colour is (colour' intensity' - colour intensity) / the scene's intensity; lights shoot
/// first, so the next step shoots it, and every vertex it reaches gains (or loses) exactly the
/// difference, the surfaces then passing it on. Logged shots keep what they shot, so vertices made
/// later gather the light as it was plus its changes. Switching a light off is intensity 0.
/// Throws rad::Error if `light` does not exist, the colour or intensity is negative or not
/// finite, or the scene gave the light intensity 0 (there is no distribution to scale).
void set_light(Solution& sol, EnergyBalance& energy, int32_t light, const Vec3& colour,
               float intensity);

/// Splits every leaf of polygon p one level (skipping leaves already at the minimum size).
/// Each new vertex gathers every shot of the log again, so its radiosity is exact, not
/// interpolated. Returns the number of new vertices. Parallel inside.
size_t force_subdivide(EditContext ctx, int32_t polygon, const VisibilityBackend& vis);

}  // namespace rad
