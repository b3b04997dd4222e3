// Light groups: the light of each group of emitters (lights and emitting surfaces, put in groups
// by the scene) solved on its own, every bounce included, so that a viewer or an engine can
// switch and dim the groups after the solve. Radiosity is linear in the emission: the groups'
// radiosities, each times its dimmer, add up to the radiosity of the scene so lit.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "solver/solver.h"

namespace rad {

/// The groups of a scene's emitters, in order of first appearance (objects, then lights); "" is
/// the default group, of every emitter given none. Only emitters count: a group holding no
/// object with emission and no light with intensity is not one.
std::vector<std::string> light_group_names(const Hierarchy& h);

/// What a group's light alone is rendered from: the solution's parts that differ from the whole
/// solve's (solution.h, energy_balance.h).
struct LightGroupState {
  std::vector<std::vector<VertexState>> vertex_states;
  std::vector<Material> materials;   // every other group's emission 0
  std::vector<LightSetting> lights;  // every other group's intensity 0
  EnergyBalance energy;
};

/// Per light group, the radiosity of every vertex of a solution's mesh.
struct LightGroupSolution {
  std::vector<std::string> names;  // light_group_names
  /// Vertex v of polygon p is entry first_vertex[p] + v of each group's array.
  std::vector<size_t> first_vertex;
  /// Per group: B = E + rho * H of the group's light alone, per vertex.
  std::vector<std::vector<Vec3>> radiosity;
  /// Per group: the shots its solve took and the unshot fraction it stopped at.
  std::vector<int64_t> shots;
  std::vector<double> unshot_fraction;
  /// Per group, when solve_light_groups was asked to keep them: its state (show_group).
  std::vector<LightGroupState> states;

  Vec3 at(size_t group, size_t p, uint32_t v) const {
    return radiosity[group][first_vertex[p] + v];
  }
};

/// Solves each light group of `solved` (a finished solve; under MPI, one rank's gathered
/// whole) on its mesh as it is, refinement off: from its emission alone (every other group's
/// objects and lights off), to the same convergence and shot limits, with the same backend.
/// One group after the other, each in a state of its own; `solved` is not changed. Empty when
/// the scene has fewer than two groups or names none. `stop` (if set) is polled before every
/// shot of every group's solve: a reason ends that group's solve where it is. `keep_states`:
/// each group's state is kept too (LightGroupSolution::states), for rendering its images.
LightGroupSolution solve_light_groups(const SolverState& solved, const VisibilityBackend& vis,
                                      const std::function<std::optional<StopReason>()>& stop = {},
                                      bool keep_states = false);

/// A state for showing the groups of `solved` one at a time (show_group): its options, scene
/// caches, solution and energy, without its shot log, kept rays and statistics.
SolverState group_view(const SolverState& solved);

/// Makes `view` (a group_view of the solve `groups` was solved from) hold group g's light alone:
/// its vertex states, materials, lights and energy. `groups` must hold its states.
void show_group(SolverState& view, const LightGroupSolution& groups, size_t g);

}  // namespace rad
