// The radiosity solution itself: the mesh of every polygon and what each of its vertices holds.
#pragma once

#include <vector>

#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "solver/texture_factors.h"

namespace rad {

/// What the solver keeps at a vertex of the radiosity mesh (whose position the mesh keeps, at
/// the same index). One record per vertex, not one array per quantity: a polygon that never
/// splits costs one allocation, not four.
struct VertexState {
  Vec3 irradiance{0.0f};  // H: radiosity gathered from all shots so far; B = E + rho * H
  Vec3 unshot{0.0f};      // radiosity received but not yet shot
  Vec3 last_gain{0.0f};   // H gathered from the current shot only (for subdivision)
  Vec3 major{0.0f};       // part of H gathered from the solver's major shots (see solver)

  /// Takes a shot's gain dh (H before the reflectance rho): into H, the current shot and, for a
  /// major shot, the major part; into the light to shoot only when the vertex `shoots` (not one
  /// deeper inside a solid than kShootingDepth, buried_vertices.h).
  void receive(const Vec3& dh, const Vec3& rho, bool major_shot, bool shoots) {
    irradiance += dh;
    if (shoots) unshot += rho * dh;
    last_gain = dh;
    if (major_shot) major += dh;
  }
};

/// A light's colour and intensity as edited (the fields of the same names in scene/light.h).
struct LightSetting {
  Vec3 colour{1.0f};
  float intensity = 0.0f;
};

/// The scene's radiosity as solved so far: per polygon (a triangle of the hierarchy) its mesh
/// and its vertices' states, and the materials and lights as edited. Keeps a pointer to the
/// hierarchy, which must outlive it.
struct Solution {
  const Hierarchy* hierarchy = nullptr;
  Mesh mesh;
  /// Per polygon, per vertex of its mesh (same indices; as long as its vertex table).
  std::vector<std::vector<VertexState>> vertex_states;
  /// Materials per hierarchy object (copied so they can be edited between shots).
  std::vector<Material> materials;
  /// Per light of the hierarchy (Hierarchy::lights): its colour and intensity, as edited.
  std::vector<LightSetting> lights;
  /// Light groups (light_groups.h): how many (0 for a scene of fewer than two), and per polygon,
  /// per vertex v and group g, at [v * group_count + g], the vertex's state under that group's
  /// light alone, kept as vertex_states keeps the whole's (empty without groups).
  size_t group_count = 0;
  std::vector<std::vector<VertexState>> group_states;
  /// With light groups: per object of the hierarchy and per light, its group's index.
  std::vector<uint32_t> object_group, light_group;
  /// Per polygon that reflects or emits by a texture, per vertex: its texture factors
  /// (solver/texture_factors.h), fixed when the vertex is made; empty for other polygons.
  std::vector<std::vector<TextureFactors>> texture_factors;

  const Material& material_of(size_t polygon) const {
    return materials[size_t(hierarchy->triangles.object[polygon])];
  }
  /// The Pure polygon p belongs to (its texture and cut-out are there).
  const SceneObject& object_of(size_t polygon) const {
    return hierarchy->objects[size_t(hierarchy->triangles.object[polygon])];
  }
  /// The reflectance rho of vertex v of polygon p: its material's, times its texture factor.
  Vec3 reflectance(size_t p, uint32_t v) const {
    const Vec3 rho = material_of(p).reflectance;
    return texture_factors[p].empty() ? rho : rho * texture_factors[p][v].reflectance;
  }
  /// The emission E of vertex v of polygon p: its material's, times its texture factor.
  Vec3 emission(size_t p, uint32_t v) const {
    const Vec3 e = material_of(p).emission;
    return texture_factors[p].empty() ? e : e * texture_factors[p][v].emission;
  }
  /// Light i's colour and intensity as edited; the scene's where the solution holds no
  /// settings (one built by hand rather than by make_solver_state).
  LightSetting light_setting(size_t i) const {
    if (lights.size() == hierarchy->lights.size()) return lights[i];
    const Light& l = hierarchy->lights[i];
    return {l.colour, l.intensity};
  }
  /// Radiosity B = E + rho * H of vertex v of polygon p.
  Vec3 radiosity(size_t p, uint32_t v) const {
    return emission(p, v) + reflectance(p, v) * vertex_states[p][v].irradiance;
  }
  /// Polygon p's vertex states under each light group (none without groups).
  const std::vector<VertexState>& group_states_of(size_t p) const {
    static const std::vector<VertexState> none;
    return group_count > 0 ? group_states[p] : none;
  }
  /// Group g's light alone at vertex v of polygon p: its radiosity B_g = E_g + rho * H_g, E_g
  /// the vertex's emission when its object is in group g.
  Vec3 group_radiosity(size_t g, size_t p, uint32_t v) const {
    const Vec3 e =
        object_group[size_t(hierarchy->triangles.object[p])] == g ? emission(p, v) : Vec3(0.0f);
    return e + reflectance(p, v) * group_states[p][v * group_count + g].irradiance;
  }
};

}  // namespace rad
