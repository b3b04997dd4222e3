#include "solver/edits.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "mesh/subdivide.h"
#include "solver/refine.h"
#include "solver/shoot.h"

namespace rad {

void set_material(SolverState& s, int32_t object, const Material& m, const VisibilityBackend& vis) {
  const Hierarchy& h = *s.hierarchy;
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
  const Material old = s.materials[size_t(object)];
  const Vec3 d_e = m.emission - old.emission, d_rho = m.reflectance - old.reflectance;
  s.materials[size_t(object)] = m;
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    for (VertexState& v : s.vertex_states[t]) v.unshot += d_e + d_rho * v.irradiance;
    s.emitted_energy += double(h.triangles.area[t]) * double(mean_component(d_e));
    s.unshot_energy[t] = polygon_unshot_energy(s, t);
  }
  // Convergence follows the new emission, as a fresh solve's would, unless the edit left next
  // to none: then the light there was is what must be shot back out.
  if (s.emitted_energy > 1e-6 * s.reference_energy) s.reference_energy = s.emitted_energy;
  // Where the new radiosity varies beyond the limit (a surface that was black was never
  // subdivided), refine now, exactly.
  std::vector<uint32_t> which;
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t)
    which.push_back(t);
  refine_after_edit(s, d_rho, vis, which);
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    s.unshot_energy[t] = polygon_unshot_energy(s, t);
  }
  update_unshot_totals(s);
}

size_t force_subdivide(SolverState& s, int32_t polygon, const VisibilityBackend& vis) {
  PolygonMesh& m = s.mesh.polygons[size_t(polygon)];
  const uint32_t made_before = uint32_t(m.vertex_count());
  std::vector<VertexState>& vs = s.vertex_states[size_t(polygon)];
  std::vector<uint32_t> leaves;
  for_each_leaf(m, [&](uint32_t e) { leaves.push_back(e); });
  std::vector<NewMidpoint> created;
  for (uint32_t e : leaves) {
    if (element_size(m, e) < 2.0f * s.min_size) continue;
    NewMidpoint c[3];
    const int n = split_element(m, e, c);
    created.insert(created.end(), c, c + n);
    ++s.stats.subdivisions;
  }
  vs.resize(m.vertex_count());
  if (s.buried.found) {
    find_buried_vertices(s.hierarchy->triangles, size_t(polygon), m, made_before, vis,
                         buried_probe(s), s.buried.moved[size_t(polygon)], s.stats.rays);
  }
  const GatherSettings settings = gather_settings(s);
  parallel_gather(created.size(), 1, s.stats, [&](size_t begin, size_t end, GatherScratch& sc) {
    for (size_t i = begin; i != end; ++i) {
      const NewMidpoint& c = created[i];
      VertexState& mid = vs[c.vertex];
      const Vec3 at = s.buried.gather_point(size_t(polygon), c.vertex, m.positions[c.vertex]);
      mid.irradiance =
          regather_shots(s, at, uint32_t(polygon), false, vis, settings, sc, &mid.major);
      mid.unshot = (vs[c.a].unshot + vs[c.b].unshot) * 0.5f;  // transient: interpolated
      mid.shot = Vec3(0.0f);
    }
  });
  s.stats.exact_midpoints += created.size();
  s.unshot_energy[size_t(polygon)] = polygon_unshot_energy(s, size_t(polygon));
  update_unshot_totals(s);
  return created.size();
}

}  // namespace rad
