#include "solver/light_groups.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>

#include "core/error.h"

namespace rad {

std::vector<std::string> light_group_names(const Hierarchy& h) {
  std::vector<std::string> names;
  auto add = [&](const std::string& g) {
    if (std::find(names.begin(), names.end(), g) == names.end()) names.push_back(g);
  };
  for (const SceneObject& o : h.objects) {
    const bool emits = o.kind == ObjectKind::Pure && max_component(o.material.emission) > 0.0f &&
                       o.triangle_count > 0;
    if (emits) add(o.group);
  }
  // A light the scene leaves off (intensity 0) may be turned on by an edit: a group it names is
  // kept for it.
  for (const Light& l : h.lights) {
    if ((l.intensity > 0.0f && max_component(l.colour) > 0.0f) || !l.group.empty()) add(l.group);
  }
  return names;
}

std::vector<std::string> light_groups_kept(const Hierarchy& h) {
  std::vector<std::string> names = light_group_names(h);
  const bool named =
      std::any_of(names.begin(), names.end(), [](const std::string& g) { return !g.empty(); });
  if (names.size() < 2 || !named) names.clear();
  return names;
}

void assign_light_groups(Solution& sol) {
  const Hierarchy& h = *sol.hierarchy;
  const std::vector<std::string> names = light_groups_kept(h);
  sol.group_count = 0;
  sol.group_states.clear();
  sol.object_group.clear();
  sol.light_group.clear();
  if (names.empty()) return;
  if (names.size() > kMaxLightGroups) {
    throw Error(
        fmt::format("the scene has {} light groups, more than the {} rad keeps apart; "
                    "put some of its emitters in the same group",
                    names.size(), kMaxLightGroups));
  }
  auto index = [&](const std::string& g) {
    const auto at = std::find(names.begin(), names.end(), g);
    return at == names.end() ? 0u : uint32_t(at - names.begin());
  };
  for (const SceneObject& o : h.objects) sol.object_group.push_back(index(o.group));
  for (const Light& l : h.lights) sol.light_group.push_back(index(l.group));
  sol.group_count = names.size();
  sol.group_states.resize(sol.vertex_states.size());
  for (size_t p = 0; p < sol.vertex_states.size(); ++p)
    sol.group_states[p].assign(sol.vertex_states[p].size() * sol.group_count, VertexState{});
  // (A solution not yet started has no vertex states: start_from_emission makes both.)
}

SolverState group_view(const SolverState& solved) {
  SolverState view;
  view.options = solved.options;
  view.scene = solved.scene;
  // The solution but its groups' states, which show_group reads from `solved`.
  const Solution& whole = solved.solution;
  Solution& sol = view.solution;
  sol.hierarchy = whole.hierarchy;
  sol.mesh = whole.mesh;
  sol.vertex_states = whole.vertex_states;
  sol.materials = whole.materials;
  sol.lights = whole.lights;
  sol.texture_factors = whole.texture_factors;
  view.energy = solved.energy;
  return view;
}

void show_group(SolverState& view, const SolverState& solved, size_t g) {
  const Solution& whole = solved.solution;
  assert(g < whole.group_count);
  Solution& sol = view.solution;
  const size_t n = whole.group_count;
  for (size_t p = 0; p < whole.vertex_states.size(); ++p) {
    for (size_t v = 0; v < whole.vertex_states[p].size(); ++v)
      sol.vertex_states[p][v] = whole.group_states[p][v * n + g];
  }
  for (size_t i = 0; i < sol.materials.size(); ++i) {
    sol.materials[i] = whole.materials[i];
    if (whole.object_group[i] != g) sol.materials[i].emission = Vec3(0.0f);
  }
  sol.lights.resize(whole.hierarchy->lights.size());
  for (size_t i = 0; i < sol.lights.size(); ++i) {
    sol.lights[i] = whole.light_setting(i);
    if (whole.light_group[i] != g) sol.lights[i].intensity = 0.0f;
  }
}

}  // namespace rad
