#include "solver/light_groups.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "solver/energy_balance.h"

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
  for (const Light& l : h.lights) {
    if (l.intensity > 0.0f && max_component(l.colour) > 0.0f) add(l.group);
  }
  return names;
}

namespace {

// The radiosity of every vertex of `sol`, flat in polygon order.
std::vector<Vec3> vertex_radiosity(const Solution& sol, const std::vector<size_t>& first_vertex) {
  std::vector<Vec3> b(first_vertex.back());
  for (size_t p = 0; p < sol.vertex_states.size(); ++p) {
    for (uint32_t v = 0; v < sol.vertex_states[p].size(); ++v)
      b[first_vertex[p] + v] = sol.radiosity(p, v);
  }
  return b;
}

}  // namespace

LightGroupSolution solve_light_groups(const SolverState& solved, const VisibilityBackend& vis,
                                      const std::function<std::optional<StopReason>()>& stop,
                                      bool keep_states) {
  const Hierarchy& h = *solved.solution.hierarchy;
  LightGroupSolution out;
  out.names = light_group_names(h);
  const bool named = std::any_of(out.names.begin(), out.names.end(),
                                 [](const std::string& g) { return !g.empty(); });
  if (!named) return {};
  const Solution& all_on = solved.solution;
  out.first_vertex.assign(all_on.vertex_states.size() + 1, 0);
  for (size_t p = 0; p < all_on.vertex_states.size(); ++p)
    out.first_vertex[p + 1] = out.first_vertex[p] + all_on.vertex_states[p].size();
  if (out.names.size() == 1) {  // one group: its light is the whole solve's
    out.radiosity.push_back(vertex_radiosity(all_on, out.first_vertex));
    out.shots.push_back(solved.shots.count);
    out.unshot_fraction.push_back(solved.energy.unshot_fraction());
    return out;
  }

  // One state for every group's solve, made once (the scene caches are the solve's own, read
  // only); each group starts it over from its own emission. One process: under MPI this runs on
  // the rank that gathered the whole solve.
  SolverState gs = group_view(solved);
  // The mesh stays as the whole solve refined it, so every group's vertices are the same.
  gs.options.subdivision_threshold = std::numeric_limits<float>::infinity();
  gs.solution.lights.resize(h.lights.size());
  for (const std::string& group : out.names) {
    for (size_t i = 0; i < h.objects.size(); ++i) {
      gs.solution.materials[i] = all_on.materials[i];
      if (h.objects[i].group != group) gs.solution.materials[i].emission = Vec3(0.0f);
    }
    for (size_t i = 0; i < h.lights.size(); ++i) {
      gs.solution.lights[i] = all_on.light_setting(i);
      if (h.lights[i].group != group) gs.solution.lights[i].intensity = 0.0f;
    }
    gs.energy = start_from_emission(gs.solution);
    update_unshot_totals(gs.energy, gs.solution, gs.scene.clusters, nullptr);
    gs.shots = ShotLog{};
    gs.kept = KeptRayStore{};
    gs.receivers = Receivers{};
    gs.stats = SolverStats{};
    solve(gs, vis, {}, stop);
    out.radiosity.push_back(vertex_radiosity(gs.solution, out.first_vertex));
    out.shots.push_back(gs.shots.count);
    out.unshot_fraction.push_back(gs.energy.unshot_fraction());
    if (keep_states) {
      out.states.push_back(
          {gs.solution.vertex_states, gs.solution.materials, gs.solution.lights, gs.energy});
    }
  }
  return out;
}

SolverState group_view(const SolverState& solved) {
  SolverState view;
  view.options = solved.options;
  view.scene = solved.scene;
  view.solution = solved.solution;
  view.energy = solved.energy;
  return view;
}

void show_group(SolverState& view, const LightGroupSolution& groups, size_t g) {
  assert(g < groups.states.size());
  const LightGroupState& state = groups.states[g];
  view.solution.vertex_states = state.vertex_states;
  view.solution.materials = state.materials;
  view.solution.lights = state.lights;
  view.energy = state.energy;
}

}  // namespace rad
