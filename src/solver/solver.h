// Progressive refinement radiosity (Cohen, Chen, Wallace, Greenberg, SIGGRAPH 1988) with
// ray-traced vertex-to-source form factors (Wallace, Elmquist, Haines, SIGGRAPH 1989), driven
// shot by shot by its caller.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "solver/solver_state.h"

namespace rad {

struct Shooter {
  int32_t cluster;
  double energy;  // what it shoots: its unshot energy (with overshooting, plus its share)
};

/// The cluster with the most unshot energy (with overshooting: the most to shoot, its unshot
/// energy plus its share of the ambient term) per vertex its shot is expected to gather (its
/// last shot's; else the mean of the last shots of clusters of about its area; else of all shots
/// so far); ties go to the lowest index. None when nothing is left to shoot. Collective under
/// MPI.
std::optional<Shooter> choose_shooter(const SolverState& s);

/// Finds the vertices of `sol`'s mesh inside solids (scene.buried) if not found yet: before the
/// first shot or edit, and the first after a checkpoint was restored, when a backend is at hand;
/// its probes' rays are counted in stats. Without shadows (options.shadows) nothing blocks a
/// buried vertex's view, and every vertex gathers where it is.
void find_buried_vertices_once(const SolverOptions& options, const Solution& sol,
                               SceneCaches& scene, SolverStats& stats,
                               const VisibilityBackend& vis);

/// One shot: choose the shooter, shoot it to every receiving vertex, refine the receivers,
/// update the energy bookkeeping and the history. Returns the record, or nothing when there
/// was nothing to shoot. Parallel inside (TBB); call from one thread. Under MPI every rank calls
/// it together and receives for its own polygons only.
std::optional<ShotRecord> step(SolverState& s, const VisibilityBackend& vis);

/// Why solve() stopped.
enum class StopReason { Converged, MaxShots, TimeLimit, NothingToShoot, Interrupted, MemoryLimit };
const char* to_string(StopReason r);

/// The stop criteria that depend on the state alone (no clock, no signal): converged (unshot <=
/// converge x emitted), or the shot limit reached. What solve() and rad serve's session stop on.
std::optional<StopReason> goal_reached(const SolverState& s);

/// Steps until unshot <= converge x emitted, or max shots, or the time limit, or `stop` (if
/// set, polled before every shot) gives a reason (a signal, the memory limit). `on_shot` (if
/// set) is called after every shot, between steps, where the state may be read. The time limit
/// counts from this call.
StopReason solve(SolverState& s, const VisibilityBackend& vis,
                 const std::function<void(const SolverState&, const ShotRecord&)>& on_shot = {},
                 const std::function<std::optional<StopReason>()>& stop = {});

}  // namespace rad
