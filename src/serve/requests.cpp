#include "serve/requests.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.h"

namespace rad {
namespace {

using nlohmann::json;

const char* kind_name(ObjectKind k) {
  switch (k) {
    case ObjectKind::Assembly:
      return "an Assembly";
    case ObjectKind::Composite:
      return "a Composite";
    case ObjectKind::Pure:
      return "a Pure";
  }
  return "?";
}

/// The body as a JSON object (an empty body is an empty object when `empty_ok`).
json parse_object(std::string_view body, bool empty_ok) {
  if (body.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    if (empty_ok) return json::object();
    throw BadRequest("expected a JSON object, got an empty body");
  }
  json j = json::parse(body.begin(), body.end(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw BadRequest("malformed JSON");
  if (!j.is_object()) throw BadRequest("expected a JSON object");
  return j;
}

void only_fields(const json& j, std::initializer_list<const char*> allowed) {
  const std::set<std::string> ok(allowed.begin(), allowed.end());
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!ok.count(it.key())) throw BadRequest(fmt::format("unknown field '{}'", it.key()));
  }
}

int32_t integer_field(const json& j, const char* name, int64_t lo, int64_t hi) {
  if (!j.contains(name)) throw BadRequest(fmt::format("missing field '{}'", name));
  const json& v = j[name];
  if (!v.is_number_integer()) throw BadRequest(fmt::format("'{}' must be an integer", name));
  const int64_t x = v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)
                        ? INT64_MAX
                        : v.get<int64_t>();
  if (x < lo || x > hi) {
    throw BadRequest(fmt::format("'{}' is {}; it must be in [{}, {}]", name, x, lo, hi));
  }
  return int32_t(x);
}

float number(const json& v, const std::string& what, double lo, double hi) {
  if (!v.is_number()) throw BadRequest(fmt::format("{} must be a number", what));
  const double x = v.get<double>();
  if (!(x >= lo && x <= hi)) {
    throw BadRequest(fmt::format("{} is {}; it must be in [{:g}, {:g}]", what, x, lo, hi));
  }
  return float(x);
}

}  // namespace

MaterialRequest parse_material_request(std::string_view body, const Hierarchy& h) {
  const json j = parse_object(body, false);
  only_fields(j, {"object", "colour", "color", "reflectivity", "emission"});
  if (h.objects.empty()) throw BadRequest("the scene has no objects");
  MaterialRequest r;
  r.object = integer_field(j, "object", 0, int64_t(h.objects.size()) - 1);
  const SceneObject& o = h.objects[size_t(r.object)];
  if (!is_pure(h, r.object)) {
    throw BadRequest(fmt::format("object {} ('{}') is {}: only Pures have a material", r.object,
                                 o.name, kind_name(o.kind)));
  }
  if (j.contains("colour") && j.contains("color")) {
    throw BadRequest("give 'colour' or 'color', not both");
  }
  const char* colour_key = j.contains("color") ? "color" : "colour";
  if (j.contains(colour_key)) {
    const json& c = j[colour_key];
    if (!c.is_array() || c.size() != 3) {
      throw BadRequest(fmt::format("'{}' must be an array of 3 numbers", colour_key));
    }
    Vec3 v;
    for (int k = 0; k < 3; ++k)
      v[k] = number(c[size_t(k)], fmt::format("{}[{}]", colour_key, k), 0, 1);
    r.patch.colour = v;
  }
  if (j.contains("reflectivity"))
    r.patch.reflectivity = number(j["reflectivity"], "'reflectivity'", 0, 1);
  if (j.contains("emission"))
    r.patch.emission = number(j["emission"], "'emission'", 0, kMaxEmission);
  if (!r.patch.colour && !r.patch.reflectivity && !r.patch.emission) {
    throw BadRequest("nothing to change: give 'colour', 'reflectivity' or 'emission'");
  }
  return r;
}

LightRequest parse_light_request(std::string_view body, const Hierarchy& h) {
  const json j = parse_object(body, false);
  only_fields(j, {"light", "colour", "color", "intensity"});
  if (h.lights.empty()) throw BadRequest("the scene has no lights");
  LightRequest r;
  r.light = integer_field(j, "light", 0, int64_t(h.lights.size()) - 1);
  if (j.contains("colour") && j.contains("color")) {
    throw BadRequest("give 'colour' or 'color', not both");
  }
  const char* colour_key = j.contains("color") ? "color" : "colour";
  if (j.contains(colour_key)) {
    const json& c = j[colour_key];
    if (!c.is_array() || c.size() != 3) {
      throw BadRequest(fmt::format("'{}' must be an array of 3 numbers", colour_key));
    }
    Vec3 v;
    for (int k = 0; k < 3; ++k)
      v[k] = number(c[size_t(k)], fmt::format("{}[{}]", colour_key, k), 0, 1);
    r.patch.colour = v;
  }
  if (j.contains("intensity"))
    r.patch.intensity = number(j["intensity"], "'intensity'", 0, kMaxLightIntensity);
  if (!r.patch.colour && !r.patch.intensity) {
    throw BadRequest("nothing to change: give 'colour' or 'intensity'");
  }
  return r;
}

int32_t parse_subdivide_request(std::string_view body, const Hierarchy& h) {
  const json j = parse_object(body, false);
  only_fields(j, {"polygon"});
  if (h.triangles.size() == 0) throw BadRequest("the scene has no polygons");
  return integer_field(j, "polygon", 0, int64_t(h.triangles.size()) - 1);
}

bool parse_restart_request(std::string_view body) {
  const json j = parse_object(body, true);
  only_fields(j, {"materials"});
  if (!j.contains("materials")) return false;
  const json& m = j["materials"];
  if (m == "current") return false;
  if (m == "original") return true;
  throw BadRequest("'materials' must be \"current\" or \"original\"");
}

ExposureRequest parse_exposure_request(std::string_view body) {
  const json j = parse_object(body, false);
  only_fields(j, {"stops", "refit"});
  ExposureRequest r;
  if (j.contains("stops")) r.stops = number(j["stops"], "'stops'", -20, 20);
  if (j.contains("refit")) {
    if (!j["refit"].is_boolean()) throw BadRequest("'refit' must be true or false");
    r.refit = j["refit"].get<bool>();
  }
  if (!r.stops && !r.refit) throw BadRequest("nothing to change: give 'stops' or 'refit': true");
  return r;
}

std::vector<float> parse_dimmers_request(std::string_view body, size_t groups) {
  if (groups == 0) {
    throw BadRequest(
        "the scene has no light groups to dim: put its emitters in groups (Group \"name\" in a "
        "description, --light-group for a model)");
  }
  const json j = parse_object(body, false);
  only_fields(j, {"dimmers"});
  if (!j.contains("dimmers") || !j["dimmers"].is_array() || j["dimmers"].size() != groups) {
    throw BadRequest(
        fmt::format("'dimmers' must be an array of {} numbers, one per light group", groups));
  }
  std::vector<float> d;
  for (size_t g = 0; g < groups; ++g)
    d.push_back(number(j["dimmers"][g], fmt::format("'dimmers'[{}]", g), 0, kMaxDimmer));
  return d;
}

ExportRequest parse_export_request(std::string_view format,
                                   const std::multimap<std::string, std::string>& params) {
  static const std::pair<const char*, ExportFormat> kFormats[] = {
      {"ply", ExportFormat::Ply},   {"off", ExportFormat::Off}, {"obj", ExportFormat::Obj},
      {"gltf", ExportFormat::Gltf}, {"glb", ExportFormat::Glb}, {"png", ExportFormat::Png}};
  ExportRequest r;
  bool known = false;
  for (const auto& [name, f] : kFormats) {
    if (format == name) r.format = f, known = true;
  }
  if (!known) {
    throw BadRequest(fmt::format("unknown export format '{}': ply, off, obj, gltf, glb or png",
                                 std::string(format)));
  }
  std::set<std::string> seen;
  for (const auto& [key, value] : params) {
    if (!seen.insert(key).second) throw BadRequest(fmt::format("parameter '{}' given twice", key));
    if (r.format != ExportFormat::Png || (key != "camera" && key != "size")) {
      throw BadRequest(fmt::format(
          "unknown parameter '{}'{}", key,
          r.format == ExportFormat::Png ? ": camera or size" : " (camera and size are for png)"));
    }
    if (key == "camera") {
      try {
        r.camera = parse_camera(value);
      } catch (const Error& e) {
        throw BadRequest(fmt::format("camera: {}", e.message()));
      }
    } else {
      char x = 0, end = 0;
      if (std::sscanf(value.c_str(), "%d%c%d%c", &r.width, &x, &r.height, &end) != 3 || x != 'x' ||
          r.width < 16 || r.height < 16 || r.width > 4096 || r.height > 4096) {
        throw BadRequest(
            fmt::format("size: expected WxH, 16 to 4096 pixels each, got '{}'", value));
      }
    }
  }
  return r;
}

const char* extension(ExportFormat f) {
  switch (f) {
    case ExportFormat::Ply:
      return ".ply";
    case ExportFormat::Off:
      return ".off";
    case ExportFormat::Obj:
      return ".obj";
    case ExportFormat::Gltf:
      return ".gltf";
    case ExportFormat::Glb:
      return ".glb";
    case ExportFormat::Png:
      return ".png";
  }
  return "";
}

const char* content_type(ExportFormat f) {
  switch (f) {
    case ExportFormat::Png:
      return "image/png";
    case ExportFormat::Gltf:
      return "model/gltf+json";
    case ExportFormat::Glb:
      return "model/gltf-binary";
    case ExportFormat::Obj:
    case ExportFormat::Off:
      return "text/plain";
    case ExportFormat::Ply:
      return "application/octet-stream";
  }
  return "application/octet-stream";
}

}  // namespace rad
