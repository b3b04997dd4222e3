// Light groups: the light of each group of emitters (lights and emitting surfaces, put in groups
// by the scene) kept apart through the whole solve, every bounce included, so that a viewer or
// an engine can switch and dim the groups after the solve. Radiosity is linear in the emission:
// every shot's gain is split between the groups by the same weights and shadow rays
// (gather.h), so the groups' radiosities, each times its dimmer, add up to the radiosity of
// the scene so lit.
#pragma once

#include <string>
#include <vector>

#include "solver/solver_state.h"

namespace rad {

/// The most light groups a scene may have: each costs a vertex state per vertex.
inline constexpr size_t kMaxLightGroups = 32;

/// The groups of a scene's emitters, in order of first appearance (objects, then lights); "" is
/// the default group, of every emitter given none. Only emitters count: a group holding no
/// object with emission and no light with intensity is not one, unless a light the scene leaves
/// off names it (an edit may turn that light on).
std::vector<std::string> light_group_names(const Hierarchy& h);

/// The light groups a solve of `h` keeps apart: its light_group_names when there are two or
/// more and one has a name, else none.
std::vector<std::string> light_groups_kept(const Hierarchy& h);

/// Sets sol's light groups from its hierarchy's (light_groups_kept): with two or more, the
/// group count, each object's and light's group index (an object or light in no group of the
/// list, one that does not emit, counts in the first) and a zero state per vertex and group.
/// Throws rad::Error beyond kMaxLightGroups.
void assign_light_groups(Solution& sol);

/// A copy of `solved` to show its light groups one at a time (show_group): its options, scene
/// caches, solution and energy, without its shot log, kept rays and statistics.
SolverState group_view(const SolverState& solved);

/// Makes `view` (a group_view of a solve with light groups) hold group g's light alone: every
/// vertex state the group's, every other group's emitters off, and no groups of its own.
void show_group(SolverState& view, const SolverState& solved, size_t g);

}  // namespace rad
