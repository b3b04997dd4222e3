#include "solver/edits.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/subdivide.h"
#include "solver/light_source.h"
#include "solver/refine.h"
#include "solver/shoot.h"
#include "solver/solver.h"
#include "solver/texture_factors.h"

namespace rad {

void set_material(EditContext ctx, int32_t object, const Material& m,
                  const VisibilityBackend& vis) {
  // The vertices an edit makes must know where to gather.
  find_buried_vertices_once(ctx.options, ctx.solution, ctx.scene, ctx.stats, vis);
  const Hierarchy& h = *ctx.solution.hierarchy;
  if (!is_pure(h, object)) {
    throw Error(fmt::format("object {} is not a Pure", object));
  }
  for (int k = 0; k < 3; ++k) {
    if (!(m.reflectance[k] >= 0.0f && m.reflectance[k] <= 1.0f) || !(m.emission[k] >= 0.0f) ||
        !std::isfinite(m.emission[k])) {
      throw Error("reflectance must be in [0, 1] and emission finite and >= 0");
    }
  }
  const SceneObject& o = h.objects[size_t(object)];
  const Material old = ctx.solution.materials[size_t(object)];
  const Vec3 d_e = m.emission - old.emission, d_rho = m.reflectance - old.reflectance;
  // A texture stays: its factors scale the new reflectance.
  ctx.solution.materials[size_t(object)] = m;
  const size_t groups = ctx.solution.group_count;
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    std::vector<VertexState>& vs = ctx.solution.vertex_states[t];
    const std::vector<TextureFactors>& factors = ctx.solution.texture_factors[t];
    // The change of emission is the object's light group's; each group's light reflects anew,
    // where the vertex shoots what it gathers (buried_vertices.h).
    const std::vector<Vec3>& positions = ctx.solution.mesh.polygons[t].positions;
    for (size_t v = 0; v < vs.size(); ++v) {
      const Vec3 e = factors.empty() ? d_e : d_e * factors[v].emission;
      Vec3 r = factors.empty() ? d_rho : d_rho * factors[v].reflectance;
      if (!vertex_shoots(ctx.scene, t, uint32_t(v), positions[v])) r = Vec3(0.0f);
      vs[v].unshot += e + r * vs[v].irradiance;
      for (size_t g = 0; g < groups; ++g) {
        VertexState& x = ctx.solution.group_states[t][v * groups + g];
        x.unshot +=
            (ctx.solution.object_group[size_t(object)] == g ? e : Vec3(0.0f)) + r * x.irradiance;
      }
    }
    ctx.energy.emitted_energy += double(h.triangles.area[t]) * double(mean_component(d_e));
    ctx.energy.unshot_energy[t] = polygon_unshot_energy(ctx.solution, t);
  }
  // Convergence follows the new emission, as a fresh solve's would, unless the edit left next
  // to none: then the light there was is what must be shot back out.
  if (ctx.energy.emitted_energy > 1e-6 * ctx.energy.reference_energy)
    ctx.energy.reference_energy = ctx.energy.emitted_energy;
  // Where the new radiosity varies beyond the limit (a surface that was black was never
  // subdivided), refine now, exactly.
  std::vector<uint32_t> which;
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t)
    which.push_back(t);
  refine_after_edit({ctx.options, ctx.energy, ctx.shots, ctx.solution, ctx.scene, ctx.stats}, d_rho,
                    vis, which);
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    ctx.energy.unshot_energy[t] = polygon_unshot_energy(ctx.solution, t);
  }
  update_unshot_totals(ctx.energy, ctx.solution, ctx.scene.clusters, ctx.ownership.ranks);
}

void set_light(Solution& sol, EnergyBalance& energy, int32_t light, const Vec3& colour,
               float intensity) {
  const std::vector<Light>& lights = sol.hierarchy->lights;
  if (light < 0 || size_t(light) >= lights.size()) {
    throw Error(fmt::format("light {} does not exist (the scene has {})", light, lights.size()));
  }
  const Light& l = lights[size_t(light)];
  if (!(intensity >= 0.0f) || !std::isfinite(intensity)) {
    throw Error(fmt::format("light '{}': intensity must be finite and >= 0", l.name));
  }
  for (int k = 0; k < 3; ++k) {
    if (!(colour[k] >= 0.0f) || !std::isfinite(colour[k])) {
      throw Error(fmt::format("light '{}': colour must be finite and >= 0", l.name));
    }
  }
  std::vector<LightSetting>& settings = sol.lights;
  // A state built without its lights' settings starts from the scene's.
  if (settings.size() != lights.size()) {
    settings.clear();
    for (const Light& x : lights) settings.push_back({x.colour, x.intensity});
  }
  LightSetting& now = settings[size_t(light)];
  // In units of the light's shots (light_source.h: light_unit); computed in double so that
  // setting the scene's own values back leaves no rounding to shoot.
  const double scale = 1.0 / double(light_unit(l));
  Vec3 d;
  for (int k = 0; k < 3; ++k) {
    d[k] = float(
        (double(colour[k]) * double(intensity) - double(now.colour[k]) * double(now.intensity)) *
        scale);
  }
  now = {colour, intensity};
  if (d == Vec3(0.0f)) return;
  energy.light_unshot[size_t(light)] += d;
  energy.emitted_energy += energy.light_power[size_t(light)] * double(mean_component(d));
  // Convergence follows the new emission, as for a material's (set_material).
  if (energy.emitted_energy > 1e-6 * energy.reference_energy)
    energy.reference_energy = energy.emitted_energy;
}

size_t force_subdivide(EditContext ctx, int32_t polygon, const VisibilityBackend& vis) {
  find_buried_vertices_once(ctx.options, ctx.solution, ctx.scene, ctx.stats, vis);
  PolygonMesh& m = ctx.solution.mesh.polygons[size_t(polygon)];
  const uint32_t made_before = uint32_t(m.vertex_count());
  std::vector<VertexState>& vs = ctx.solution.vertex_states[size_t(polygon)];
  std::vector<uint32_t> leaves;
  for_each_leaf(m, [&](uint32_t e) { leaves.push_back(e); });
  std::vector<NewMidpoint> created;
  for (uint32_t e : leaves) {
    if (element_size(m, e) < min_split_size(ctx.scene)) continue;
    NewMidpoint c[3];
    const int n = split_element(m, e, c);
    created.insert(created.end(), c, c + n);
    ++ctx.stats.subdivisions;
  }
  vs.resize(m.vertex_count());
  const size_t groups = ctx.solution.group_count;
  if (groups > 0) ctx.solution.group_states[size_t(polygon)].resize(m.vertex_count() * groups);
  std::vector<TextureFactors>& factors = ctx.solution.texture_factors[size_t(polygon)];
  if (!factors.empty()) {
    factors.resize(m.vertex_count());
    const Triangles& tris = ctx.solution.hierarchy->triangles;
    const SceneObject& object = ctx.solution.object_of(size_t(polygon));
    // Each new vertex stands for the smallest leaf it is a corner of.
    std::vector<float> area(m.vertex_count() - made_before, std::numeric_limits<float>::max());
    for_each_leaf(m, [&](uint32_t e) {
      for (const uint32_t v : m.elements[e].v)
        if (v >= made_before)
          area[v - made_before] = std::min(area[v - made_before], m.elements[e].area);
    });
    for (uint32_t v = made_before; v < m.vertex_count(); ++v) {
      factors[v] =
          texture_factor(tris, size_t(polygon), object, m.positions[v], area[v - made_before]);
    }
  }
  if (ctx.scene.buried.found && ctx.options.shadows) {
    find_buried_vertices(ctx.solution.hierarchy->triangles, size_t(polygon), m, made_before, vis,
                         buried_probe(ctx.scene), ctx.scene.buried.moved[size_t(polygon)],
                         ctx.scene.buried.covered[size_t(polygon)], ctx.stats.rays);
  }
  const GatherSettings settings = gather_settings(ctx.options, ctx.scene, ctx.energy);
  parallel_gather(created.size(), 1, ctx.stats, [&](size_t begin, size_t end, GatherScratch& sc) {
    for (size_t i = begin; i != end; ++i) {
      const NewMidpoint& c = created[i];
      VertexState& mid = vs[c.vertex];
      const Vec3 at =
          ctx.scene.buried.gather_point(size_t(polygon), c.vertex, m.positions[c.vertex]);
      sc.group_all.resize(groups), sc.group_major.resize(groups);
      mid.irradiance = regather_shots(*ctx.solution.hierarchy, ctx.scene.clusters, ctx.shots, at,
                                      uint32_t(polygon), false, vis, settings, sc, &mid.major,
                                      sc.group_all, sc.group_major);
      mid.unshot = (vs[c.a].unshot + vs[c.b].unshot) * 0.5f;  // transient: interpolated
      mid.last_gain = Vec3(0.0f);
      for (size_t g = 0; g < groups; ++g) {
        std::vector<VertexState>& gs = ctx.solution.group_states[size_t(polygon)];
        VertexState& x = gs[c.vertex * groups + g];
        x.irradiance = sc.group_all[g], x.major = sc.group_major[g];
        x.unshot = (gs[c.a * groups + g].unshot + gs[c.b * groups + g].unshot) * 0.5f;
        x.last_gain = Vec3(0.0f);
      }
    }
  });
  ctx.stats.exact_midpoints += created.size();
  ctx.energy.unshot_energy[size_t(polygon)] = polygon_unshot_energy(ctx.solution, size_t(polygon));
  update_unshot_totals(ctx.energy, ctx.solution, ctx.scene.clusters, ctx.ownership.ranks);
  return created.size();
}

}  // namespace rad
