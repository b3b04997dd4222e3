#include "solver/solver_state.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>

#include "mesh/sample_points.h"
#include "mesh/subdivide.h"
#include "solver/light_groups.h"
#include "solver/light_source.h"
#include "solver/texture_factors.h"
#include "visibility/segment.h"

namespace rad {

float scene_size(const Hierarchy& h) {
  // Ritter's bounding sphere (Graphics Gems, 1990): distances only, so the same however the
  // scene is turned, and within a few percent of the smallest sphere (a box's diagonal exactly).
  const auto& corners = h.triangles.corners;
  if (corners.empty()) return 0.0f;
  auto farthest = [&](const DVec3& from) {
    DVec3 best = from;
    double d2 = -1.0;
    for (const auto& c : corners) {
      for (const Vec3& p : c) {
        const DVec3 q(p);
        if (glm::dot(q - from, q - from) > d2) d2 = glm::dot(q - from, q - from), best = q;
      }
    }
    return best;
  };
  const DVec3 y = farthest(DVec3(corners[0][0])), z = farthest(y);
  DVec3 centre = (y + z) * 0.5;
  double r = glm::length(z - y) * 0.5;
  for (const auto& c : corners) {
    for (const Vec3& p : c) {
      const double d = glm::length(DVec3(p) - centre);
      if (d > r) {  // grow the sphere just enough to take p
        const double grown = (r + d) * 0.5;
        centre += (DVec3(p) - centre) * ((grown - r) / d);
        r = grown;
      }
    }
  }
  return float(2.0 * r);
}

EnergyBalance start_from_emission(Solution& sol) {
  const Hierarchy& h = *sol.hierarchy;
  EnergyBalance energy;
  energy.unshot_energy.assign(h.triangles.size(), UnshotEnergy{});
  double total_area = 0.0;
  sol.vertex_states.resize(h.triangles.size());
  sol.group_states.resize(sol.group_count > 0 ? h.triangles.size() : 0);
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const Vec3 e = sol.material_of(t).emission;
    sol.vertex_states[t].assign(sol.mesh.polygons[t].vertex_count(), VertexState{.unshot = e});
    if (!sol.texture_factors[t].empty()) {
      for (uint32_t v = 0; v < sol.vertex_states[t].size(); ++v)
        sol.vertex_states[t][v].unshot = sol.emission(t, v);
    }
    // With light groups, a vertex's emission is its object's group's light.
    if (sol.group_count > 0) {
      const size_t n = sol.group_count, g = sol.object_group[size_t(h.triangles.object[t])];
      sol.group_states[t].assign(sol.vertex_states[t].size() * n, VertexState{});
      for (uint32_t v = 0; v < sol.vertex_states[t].size(); ++v)
        sol.group_states[t][v * n + g].unshot = sol.vertex_states[t][v].unshot;
    }
    energy.unshot_energy[t] = polygon_unshot_energy(sol, t);
    energy.emitted_energy += energy.unshot_energy[t].sum;
    total_area += h.triangles.area[t];
  }
  // The lights shoot first (solver.cpp), their power counted with the surfaces' emission. What
  // a light shoots is in units of its shots' intensity (light_source.h: light_unit): its
  // setting over that.
  // (At the scene's own intensity the ratio is exactly 1.)
  for (size_t i = 0; i < h.lights.size(); ++i) {
    const Light shooting = shooting_light(h.lights[i]);
    const LightSetting& now = sol.lights[i];
    energy.light_unshot.push_back(now.colour * (now.intensity / shooting.intensity));
    energy.light_power.push_back(light_power(shooting, h.bounds));
  }
  energy.emitted_energy += energy.light_unshot_energy();
  energy.reference_energy = energy.emitted_energy;
  energy.total_area = total_area;
  energy.radiosity_scale = total_area > 0.0 ? float(energy.emitted_energy / total_area) : 1.0f;
  if (!(energy.radiosity_scale > 0.0f)) energy.radiosity_scale = 1.0f;
  return energy;
}

SolverState make_solver_state(const Hierarchy& h, const SolverOptions& options) {
  SolverState s;
  s.options = options;
  Solution& sol = s.solution;
  SceneCaches& scene = s.scene;
  EnergyBalance& energy = s.energy;
  sol.hierarchy = &h;
  sol.mesh = make_mesh(h);
  // Default sizes: fractions of the scene's size (about 3.8 mm and 60 mm in the 0.55 m Cornell
  // box).
  const float size = scene_size(h);
  scene.min_size =
      options.min_size > 0.0f ? options.min_size : size / SolverOptions::kMinSizeDivisor;
  scene.max_size =
      options.max_size > 0.0f ? options.max_size : size / SolverOptions::kMaxSizeDivisor;
  scene.max_size = std::max(scene.max_size, 2.0f * scene.min_size);
  // The initial mesh: uniform splits down to max_size (vertices have no radiosity yet).
  tbb::parallel_for(size_t(0), sol.mesh.polygons.size(), [&](size_t p) {
    PolygonMesh& m = sol.mesh.polygons[p];
    std::vector<uint32_t> big;
    for (bool any = true; any;) {
      big.clear();
      for_each_leaf(m, [&](uint32_t e) {
        if (longest_edge(m, e) > scene.max_size) big.push_back(e);
      });
      NewMidpoint created[3];
      for (uint32_t e : big) split_element(m, e, created);
      any = !big.empty();
    }
  });
  sol.materials.reserve(h.objects.size());
  for (const SceneObject& o : h.objects) sol.materials.push_back(o.material);
  for (const Light& l : h.lights) sol.lights.push_back({l.colour, l.intensity});
  sol.texture_factors.resize(h.triangles.size());
  tbb::parallel_for(size_t(0), h.triangles.size(), [&](size_t t) {
    if (is_textured(h.triangles, t, sol.object_of(t))) {
      sol.texture_factors[t] =
          initial_texture_factors(h.triangles, t, sol.object_of(t), sol.mesh.polygons[t]);
    }
  });
  assign_light_groups(sol);
  // Overshooting lends a shooter the ambient light it will get back, to be paid back by
  // whatever light arrives; a light group's loan would be paid back by other groups' light and
  // its solution left wrong where they cancel. Without it (and without edits that lower a
  // light) every group's unshot light stays positive and at most the whole's.
  if (sol.group_count > 0) s.options.overshoot = false;
  energy = start_from_emission(sol);
  scene.shadow_offset = shadow_offset(h.bounds);
  scene.shooting_lights = shooting_lights(h.lights);
  assert(options.sample_grid >= 1 && options.max_sample_grid <= 64);
  const int max_m = std::max(options.sample_grid, options.max_sample_grid);
  // A cluster's n <= max_m^2 strata each stand for at most one initial element's square: its
  // area, not its width, bounds it, so a tessellated wall splits as its two triangles would.
  const double side = double(max_m) * double(scene.max_size);
  scene.clusters = make_clusters(h, side * side);
  scene.shared = find_shared_vertices(sol.mesh, scene.clusters);
  if (options.shadows && options.occlusion_culling)
    scene.culling = make_occlusion_culling(h, scene.shadow_offset);
  update_unshot_totals(energy, sol, scene.clusters, s.ownership.ranks);
  scene.barycentric_grids.resize(size_t(4 * max_m) + 1);
  for (int q = 1; q <= 4 * max_m; ++q)
    scene.barycentric_grids[size_t(q)] = regular_sample_barycentrics(q);
  return s;
}

}  // namespace rad
