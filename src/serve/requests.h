// Validation of everything a client sends: JSON bodies and query parameters become typed
// requests, or a BadRequest whose message goes back with status 400.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "export/camera.h"
#include "hierarchy/hierarchy.h"
#include "serve/material_controls.h"

namespace rad {

/// A request rad will not act on; what() is a sentence for the client.
class BadRequest : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// {"object": <id of a Pure>, "colour": [r, g, b], "reflectivity": r, "emission": e}: at least
/// one of the three controls ("color" is accepted for "colour"), each in range (see
/// controls_error). Throws BadRequest for malformed JSON, unknown or missing fields, wrong
/// types, an unknown object, an object that is not a Pure, or a value out of range.
struct MaterialRequest {
  int32_t object = -1;
  MaterialPatch patch;
};
MaterialRequest parse_material_request(std::string_view body, const Hierarchy& h);

/// {"light": <index into /api/scene's lights>, "colour": [r, g, b], "intensity": i}: at least one
/// of the two ("color" is accepted), the colour's channels in [0, 1], the intensity in candela
/// (point, spot) or lux (directional) in [0, kMaxLightIntensity]; 0 switches the light off.
/// Throws BadRequest for malformed JSON, unknown or missing fields, wrong types, an unknown
/// light, a light the scene gave intensity 0, or a value out of range.
struct LightRequest {
  int32_t light = -1;
  LightPatch patch;
};
LightRequest parse_light_request(std::string_view body, const Hierarchy& h);

/// {"polygon": <index>} -> the polygon. Throws BadRequest as above.
int32_t parse_subdivide_request(std::string_view body, const Hierarchy& h);

/// Empty body or {"materials": "current" | "original"} -> whether to go back to the scene's.
bool parse_restart_request(std::string_view body);

/// {"stops": s} with s in [-20, 20] and/or {"refit": true}.
struct ExposureRequest {
  std::optional<float> stops;
  bool refit = false;
};
ExposureRequest parse_exposure_request(std::string_view body);

/// {"dimmers": [d0, d1, ...]}: one factor per light group of the scene (/api/scene's
/// light_groups, `groups` of them), each in [0, kMaxDimmer]. Throws BadRequest for malformed
/// JSON, unknown or missing fields, a scene without light groups, another count or a value out
/// of range.
inline constexpr float kMaxDimmer = 100.0f;
std::vector<float> parse_dimmers_request(std::string_view body, size_t groups);

/// GET /api/export.<format>?camera=ex,ey,ez,tx,ty,tz[,fov]&size=WxH (camera and size: PNG only).
enum class ExportFormat : uint8_t { Ply, Off, Obj, Gltf, Glb, Png };
struct ExportRequest {
  ExportFormat format = ExportFormat::Ply;
  std::optional<Camera> camera;  // none: default_camera
  int width = 800, height = 800;
};
/// Throws BadRequest for an unknown format or parameter, a malformed camera, a size outside
/// 16..4096 pixels per side.
ExportRequest parse_export_request(std::string_view format,
                                   const std::multimap<std::string, std::string>& params);
const char* extension(ExportFormat f);     // ".ply", ...
const char* content_type(ExportFormat f);  // "application/octet-stream", "image/png", ...

}  // namespace rad
