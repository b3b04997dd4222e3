#include "serve/responses.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <nlohmann/json.hpp>

#include "solver/light_groups.h"

namespace rad {
namespace {

using nlohmann::json;
static_assert(std::endian::native == std::endian::little, "buffers are sent as stored");

json vec(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

void append(std::string& out, const void* data, size_t bytes) {
  out.append(static_cast<const char*>(data), bytes);
}

std::string header(uint32_t magic, const Snapshot& s, size_t indices) {
  const uint32_t h[8] = {magic,
                         uint32_t(s.version),
                         uint32_t(s.mesh_version),
                         uint32_t(s.mesh.position().size()),
                         uint32_t(indices),
                         0,
                         0,
                         0};
  std::string out;
  append(out, h, sizeof h);
  return out;
}

}  // namespace

std::string scene_json(const Hierarchy& h, const Camera& camera, double converge) {
  json objects = json::array();
  float brightest = 0.0f;
  for (size_t i = 0; i < h.objects.size(); ++i) {
    const SceneObject& o = h.objects[i];
    objects.push_back({{"id", i},
                       {"name", o.name},
                       {"kind", to_string(o.kind)},
                       {"parent", o.parent},
                       {"children", o.children},
                       {"first_triangle", o.first_triangle},
                       {"triangle_count", o.triangle_count}});
    brightest = std::max(brightest, max_component(o.material.emission));
  }
  json lights = json::array();
  for (size_t i = 0; i < h.lights.size(); ++i) {
    const Light& l = h.lights[i];
    json j{
        {"id", i}, {"name", l.name}, {"kind", to_string(l.kind)}, {"unit", intensity_unit(l.kind)}};
    if (l.kind != LightKind::Directional) j["position"] = vec(l.position);
    if (l.kind != LightKind::Point) j["direction"] = vec(l.direction);
    lights.push_back(std::move(j));
  }
  return json{{"name", h.scene_name},
              {"objects", objects},
              {"lights", lights},
              {"light_groups", light_groups_kept(h)},
              {"roots", h.roots},
              {"bounds", {{"min", vec(h.bounds.lo)}, {"max", vec(h.bounds.hi)}}},
              {"camera",
               {{"eye", vec(camera.eye)},
                {"target", vec(camera.target)},
                {"up", vec(camera.up)},
                {"fov", camera.fov_y_deg}}},
              {"max_emission", brightest},
              {"converge", converge}}
      .dump();
}

std::string status_json(const Hierarchy& h, const Snapshot& s) {
  json objects = json::array();
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const ObjectSnapshot& o = s.objects[i];
    json j{{"elements", o.elements}};
    if (h.objects[i].kind == ObjectKind::Pure) {
      j["colour"] = vec(o.controls.colour);
      j["reflectivity"] = o.controls.reflectivity;
      j["emission"] = o.controls.emission;
    }
    objects.push_back(std::move(j));
  }
  json lights = json::array();
  for (const LightControls& l : s.lights)
    lights.push_back({{"colour", vec(l.colour)}, {"intensity", l.intensity}});
  json history = json::array();
  for (const auto& [shot, fraction] : s.history) history.push_back(json::array({shot, fraction}));
  return json{
      {"version", s.version},
      {"mesh_version", s.mesh_version},
      {"status", to_string(s.status)},
      {"shots", s.shots},
      {"unshot_fraction", s.unshot_fraction},
      {"rays_per_second", s.rays_per_second},
      {"seconds", s.seconds},
      {"snapshot_ms", 1e3 * s.build_seconds},
      {"elements", s.elements},
      {"vertices", s.mesh.position().size()},
      {"faces", s.mesh.face_count()},
      {"exposure",
       {{"scale", s.tone.scale}, {"stops", s.exposure_stops}, {"locked", s.exposure_locked}}},
      {"objects", objects},
      {"lights", lights},
      {"dimmers", s.dimmers},
      {"history", history},
      {"notice", s.notice}}
      .dump();
}

std::string mesh_buffer(const Snapshot& s) {
  const MeshGeometry& g = *s.mesh.geometry;
  std::string out = header(kMeshMagic, s, g.indices.size());
  out.reserve(out.size() + g.position.size() * 24 + g.indices.size() * 4 +
              g.face_polygon.size() * 4);
  static_assert(sizeof(Vec3) == 12);
  append(out, g.position.data(), g.position.size() * sizeof(Vec3));
  append(out, s.colour.data(), s.colour.size() * sizeof(Vec3));
  append(out, g.indices.data(), g.indices.size() * sizeof(uint32_t));
  append(out, g.face_polygon.data(), g.face_polygon.size() * sizeof(int32_t));
  return out;
}

std::string colour_buffer(const Snapshot& s) {
  std::string out = header(kColourMagic, s, 0);
  append(out, s.colour.data(), s.colour.size() * sizeof(Vec3));
  return out;
}

}  // namespace rad
