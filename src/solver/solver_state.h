// Everything the progressive solver knows between two shots, in named parts; callers may read
// it any time between steps (the interactive mode edits materials here and continues).
#pragma once

#include "hierarchy/hierarchy.h"
#include "solver/energy_balance.h"
#include "solver/kept_rays.h"
#include "solver/options.h"
#include "solver/ownership.h"
#include "solver/receivers.h"
#include "solver/scene_caches.h"
#include "solver/shot_log.h"
#include "solver/solution.h"
#include "solver/solver_stats.h"

namespace rad {

/// The solver's state, part by part. Functions that need one part take that part, or a view
/// naming the parts they read (const) and write (ShotContext, RefineContext, EditContext), so
/// their signatures say what they read and write; the loop that steps the solve (solver.h),
/// checkpoints and the ranks' distribution take the whole.
struct SolverState {
  SolverOptions options;
  Solution solution;     // the mesh, each vertex's radiosity, the materials
  SceneCaches scene;     // clusters, shared and buried vertices, culling, element sizes
  EnergyBalance energy;  // unshot energies and the exact totals convergence is tested on
  ShotLog shots;         // the shots taken, for gathering again, and the history
  KeptRayStore kept;     // shadow-ray answers kept between shots of a cluster
  Ownership ownership;   // under MPI: what this rank receives for
  Receivers receivers;   // the polygons the last shot reached
  SolverStats stats;
};

/// The diameter of a sphere that holds every corner, about the smallest: what the default
/// element sizes scale with. Unlike the bounding box's diagonal it does not change when the
/// scene is turned (the Cornell box turned 30 and 20 degrees has a box diagonal 1.47 times its
/// own, and refined one level less); for an axis-aligned box the two are equal.
float scene_size(const Hierarchy& h);

/// Every vertex of `sol`'s mesh back to before the first shot: H = 0 and unshot radiosity = its
/// emission E (materials as in sol.materials, texture factors included), each light's whole
/// light (as in sol.lights) still to shoot; with light groups, each group's vertex states the
/// same with its own emitters' E (assign_light_groups). Returns the energy bookkeeping of that
/// start (without the cluster totals: update_unshot_totals).
EnergyBalance start_from_emission(Solution& sol);

/// The state before the first shot: the unsplit mesh, emitters' unshot radiosity = emission.
/// Keeps a pointer to `h`, which must outlive the state.
SolverState make_solver_state(const Hierarchy& h, const SolverOptions& options);

}  // namespace rad
