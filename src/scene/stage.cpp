#include "scene/stage.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <numbers>

#include "scene/description.h"

namespace rad {

namespace {

constexpr float kDegree = std::numbers::pi_v<float> / 180.0f;

// Where the stage camera looks from: in front (+z) and 30 degrees to the right, 25 degrees up,
// the three-quarter view of a product shot that shows the front, one side and the top.
constexpr float kViewAzimuthDeg = 30.0f, kViewElevationDeg = 25.0f;
constexpr float kLightShift = 0.3f;

// The form factor from a point facing up to a parallel rectangle a x b whose corner lies c
// straight above it (Howell's catalogue, C-11).
double corner_form_factor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * std::numbers::pi);
}

// A horizontal rectangle at height y, facing up (+y) or down, as two triangles whose corner
// order gives that front face.
std::vector<std::array<Vec3, 3>> rectangle(Vec2 lo, Vec2 hi, float y, bool up) {
  const Vec3 a(lo.x, y, lo.y), b(lo.x, y, hi.y), c(hi.x, y, hi.y), d(hi.x, y, lo.y);
  if (up) return {{a, b, c}, {a, c, d}};
  return {{a, c, b}, {a, d, c}};
}

// A number as a description would be written: whole above a thousand (no exponent), else four
// significant digits.
std::string number(double v) {
  return std::abs(v) >= 1000.0 && std::abs(v) < 1e12 ? fmt::format("{:.0f}", v)
                                                     : fmt::format("{:.4g}", v);
}

}  // namespace

SunAngles parse_sun_angles(const std::string& text) {
  SunAngles s;
  if (text.empty()) return s;
  const std::string how =
      "--sun takes ELEVATION,AZIMUTH in degrees (e.g. --sun 30,60: 30 degrees above the horizon, "
      "60 from the front toward +x), or nothing for 45,-45";
  const size_t comma = text.find(',');
  if (comma == std::string::npos) throw Error(how + "; got '" + text + "'");
  const char* end = text.data() + text.size();
  const auto e = std::from_chars(text.data(), text.data() + comma, s.elevation_deg);
  const auto a = std::from_chars(text.data() + comma + 1, end, s.azimuth_deg);
  if (e.ec != std::errc() || e.ptr != text.data() + comma || a.ec != std::errc() || a.ptr != end) {
    throw Error(how + "; got '" + text + "' (put --sun after the scene and output when it " +
                "takes no value)");
  }
  if (!(s.elevation_deg > 0.0f && s.elevation_deg <= 90.0f)) {
    throw Error(
        fmt::format("--sun {}: the elevation must be above 0 and at most 90 degrees (90: "
                    "straight overhead)",
                    text));
  }
  if (!(std::abs(s.azimuth_deg) <= 360.0f)) {
    throw Error(fmt::format("--sun {}: the azimuth must lie within -360 to 360 degrees", text));
  }
  return s;
}

Stage plan_stage(const Aabb& model, const StageOptions& options) {
  const Vec3 ext = model.extent();
  const float footprint = std::max(ext.x, ext.z);
  const float size = std::max(footprint, ext.y);
  if (model.empty() || !std::isfinite(model.magnitude()) || !(size > 0.0f)) {
    throw Error("--stage: the model has no extent to set a stage around");
  }
  Stage s;
  s.model = model;
  // Room around the model for its soft shadow: a quarter of its footprint, or half its height
  // for a tall one (a lamp post).
  const float margin = std::max(0.25f * footprint, 0.5f * ext.y);
  const Vec2 lo(model.lo.x, model.lo.z), hi(model.hi.x, model.hi.z);
  s.floor_y = model.lo.y;
  s.floor_lo = lo - margin;
  s.floor_hi = hi + margin;

  // The light: over the footprint's centre, a little wider than the footprint (at least half
  // the model's size a side, so a thin model is not lit by a sliver), as high as gives the floor
  // below it a form factor of kLightFormFactor, and a quarter of the model's size above its top
  // at least. It is then about 27 degrees across seen from the floor: soft shadows, above the
  // stage camera's view in a square, wide or tall image, and an exitance (illuminance / form
  // factor) well above what any surface it and the sun light reflects, so the automatic
  // exposure, which takes the brightest values for light sources, still sees the sunlit
  // surfaces as surfaces.
  constexpr double kLightFormFactor = 0.08;
  // Moved toward the camera's side by a fraction of the model's size, as a photographer's key
  // light is: the faces the camera sees get light at an angle, not at grazing incidence.
  const float va = kViewAzimuthDeg * kDegree, ve = kViewElevationDeg * kDegree;
  s.view_direction = Vec3(std::sin(va) * std::cos(ve), std::sin(ve), std::cos(va) * std::cos(ve));
  const Vec2 centre = 0.5f * (lo + hi) + kLightShift * size * Vec2(std::sin(va), std::cos(va));
  const Vec2 half = 0.5f * glm::max(Vec2(ext.x, ext.z), Vec2(0.5f * size)) + 0.5f * margin;
  s.light_lo = centre - half;
  s.light_hi = centre + half;
  auto form_factor = [&](double height) {
    return 4.0 * corner_form_factor(half.x, half.y, height);
  };
  double near = 0.0, far = double(size);  // the form factor falls as the light rises
  while (form_factor(far) > kLightFormFactor) far *= 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (near + far);
    (form_factor(mid) > kLightFormFactor ? near : far) = mid;
  }
  s.light_y = std::max(s.floor_y + float(far), model.hi.y + 0.25f * size);
  s.illuminance_below = options.sun ? kStageSkyIlluminance : kStageIlluminance;
  s.exitance =
      float(double(s.illuminance_below) / form_factor(double(s.light_y) - double(s.floor_y)));

  if (options.sun) {
    s.sun = options.sun;
    const float e = options.sun->elevation_deg * kDegree, a = options.sun->azimuth_deg * kDegree;
    const Vec3 toward_sun(std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e));
    s.sun_direction = -toward_sun;
    s.sun_illuminance = kStageSunIlluminance;
    // The floor reaches past the shadow of the model's top too, up to three model sizes (a
    // low sun's shadow runs off any floor).
    const float reach = std::min(ext.y / std::tan(e), 3.0f * size);
    const Vec2 away = -Vec2(std::sin(a), std::cos(a)) * reach;
    s.floor_lo = glm::min(s.floor_lo, lo + away - margin);
    s.floor_hi = glm::max(s.floor_hi, hi + away + margin);
  }
  return s;
}

Stage add_stage(SceneDescription& scene, const StageOptions& options) {
  // A model's scene holds its triangles placed (model_scene.h): no transforms or copies.
  Aabb box;
  for (const ObjectDescription& o : scene.objects)
    for (const std::array<Vec3, 3>& t : o.triangles)
      for (const Vec3& p : t) box.extend(p);
  if (box.empty()) throw Error(SourceLoc{scene.path}, "--stage: the model has no triangles");
  Stage s;
  try {
    s = plan_stage(box, options);
  } catch (const Error& e) {
    throw Error(SourceLoc{scene.path}, e.message());
  }

  const SourceLoc loc{scene.path};
  const int32_t root = int32_t(scene.objects.size());
  ObjectDescription stage;
  stage.name = "stage";
  stage.kind = ObjectKind::Assembly;
  stage.loc = loc;
  scene.objects.push_back(std::move(stage));
  scene.roots.push_back(root);
  auto add = [&](ObjectDescription o) {
    scene.objects[size_t(root)].children.push_back(int32_t(scene.objects.size()));
    scene.objects.push_back(std::move(o));
  };

  ObjectDescription floor;
  floor.name = "stage floor";
  floor.loc = loc;
  floor.material = Material{Vec3(kStageFloorReflectance), Vec3(0.0f)};
  floor.triangles = rectangle(s.floor_lo, s.floor_hi, s.floor_y, /*up=*/true);
  add(std::move(floor));

  // It reflects nothing: an emitter alone, whose light is all the model and floor receive.
  ObjectDescription light;
  light.name = "stage light";
  light.loc = loc;
  light.material = Material{Vec3(0.0f), Vec3(s.exitance)};
  light.triangles = rectangle(s.light_lo, s.light_hi, s.light_y, /*up=*/false);
  add(std::move(light));

  if (s.sun) {
    ObjectDescription sun;
    sun.name = "stage sun";
    sun.loc = loc;
    Light l;
    l.name = sun.name;
    l.kind = LightKind::Directional;
    l.loc = loc;
    l.direction = s.sun_direction;
    l.intensity = s.sun_illuminance;
    sun.light = std::move(l);
    add(std::move(sun));
  }
  if (scene.model) scene.model->stage = s;
  return s;
}

std::string describe_stage(const Stage& s, double metres_per_unit) {
  const Vec2 floor = s.floor_hi - s.floor_lo, light = s.light_hi - s.light_lo;
  const double lumens =
      double(s.exitance) * double(light.x) * double(light.y) * metres_per_unit * metres_per_unit;
  std::string line = fmt::format(
      "Stage: floor {} x {} at y {} (reflectance {}); light {} x {} at y {}, Emission {} ({} lm; "
      "{} lux on the floor below it)",
      number(floor.x), number(floor.y), number(s.floor_y), kStageFloorReflectance, number(light.x),
      number(light.y), number(s.light_y), number(s.exitance), number(lumens),
      number(s.illuminance_below));
  if (s.sun) {
    line += fmt::format("; sun at elevation {}, azimuth {}, {} lux", number(s.sun->elevation_deg),
                        number(s.sun->azimuth_deg), number(s.sun_illuminance));
  }
  return line;
}

}  // namespace rad
