#include "scene/description_writer.h"

#include <fmt/format.h>

#include <filesystem>
#include <numbers>
#include <string>

namespace rad {

namespace {

// One colour for both: the reflectance's if any, else the emission's.
Vec3 written_color(const Material& m) {
  const float rho = max_component(m.reflectance), e = max_component(m.emission);
  return rho > 0.0f ? m.reflectance / rho : (e > 0.0f ? m.emission / e : Vec3(1.0f));
}

// A name as a description string: strings end at a quote or a line break, so those become ' and
// a space (a model's names may hold anything).
std::string quoted(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? '\'' : (c == '\n' || c == '\r' ? ' ' : c);
  return q + '"';
}

// A Light object's body, as the parser reads it.
void write_light(const Light& l, const std::string& pad, std::ostream& out) {
  auto vec = [](const Vec3& v) { return fmt::format("<{:.9g} {:.9g} {:.9g}>", v.x, v.y, v.z); };
  constexpr double kDeg = 180.0 / std::numbers::pi;
  const char* type = l.kind == LightKind::Point  ? "Point"
                     : l.kind == LightKind::Spot ? "Spot"
                                                 : "Directional";
  out << pad << "Type " << type;
  if (l.kind != LightKind::Directional) out << " Position " << vec(l.position);
  if (l.kind != LightKind::Point || l.photometry) out << " Direction " << vec(l.direction);
  out << " Color " << vec(l.colour) << " Intensity " << fmt::format("{:.9g}", l.intensity);
  if (l.kind == LightKind::Spot) {
    out << fmt::format(" Cone {:.9g} {:.9g}", l.inner_cone * kDeg, l.outer_cone * kDeg);
  }
  if (l.kind == LightKind::Directional) {
    out << fmt::format(" AngularDiameter {:.9g}", l.angular_diameter * kDeg);
  }
  if (l.photometry) {
    std::error_code ec;
    const std::filesystem::path ies = std::filesystem::absolute(l.photometry->path, ec);
    out << " Ies " << quoted(ec ? l.photometry->path : ies.string()) << " IesC0 "
        << vec(l.photometric_up);
  }
  if (!l.group.empty()) out << " Group " << quoted(l.group);
  out << "\n";
}

}  // namespace

bool material_is_writable(const Material& m) {
  const float e = max_component(m.emission);
  if (!(e > 0.0f)) return true;
  const Vec3 c = written_color(m), back = c * (mean_component(m.emission) / mean_component(c));
  return glm::all(glm::lessThanEqual(glm::abs(back - m.emission), Vec3(1e-5f * e)));
}

void write_description(const SceneDescription& scene, std::ostream& out) {
  auto vec = [](const Vec3& v) { return fmt::format("<{:.9g} {:.9g} {:.9g}>", v.x, v.y, v.z); };
  auto write = [&](auto&& self, int32_t id, int depth) -> void {
    const ObjectDescription& o = scene.objects[id];
    std::string pad(2 * depth, ' ');
    out << pad << "Object " << quoted(o.name) << ' ';
    if (o.copy_of >= 0) {  // the latest complete object of that name, as when it was parsed
      out << "Copy " << quoted(scene.objects[size_t(o.copy_of)].name);
    } else if (o.light) {
      out << "Light";
    } else {
      out << to_string(o.kind);
    }
    for (const Transform& t : o.transforms) {
      const auto v = [](const DVec3& d) {
        return fmt::format("<{:.17g} {:.17g} {:.17g}>", d.x, d.y, d.z);
      };
      switch (t.kind) {
        case Transform::Kind::Translate:
          out << " Translate " << v(t.v);
          break;
        case Transform::Kind::Rotate:
          out << " Rotate " << v(t.v) << fmt::format(" {:.17g}", t.degrees);
          break;
        case Transform::Kind::Scale:
          out << " Scale " << v(t.v);
          break;
      }
    }
    const ObjectFlags& f = o.flags;
    if (f.casts_shadows) out << " CastsShadows " << (*f.casts_shadows ? "Yes" : "No");
    if (f.receives_shadows) out << " ReceivesShadows " << (*f.receives_shadows ? "Yes" : "No");
    if (f.two_sided) out << " TwoSided " << (*f.two_sided ? "Yes" : "No");
    if (f.has_lights) {
      out << " Lights {";
      for (const NamedObject& n : f.lights) out << ' ' << quoted(n.name);
      out << " }";
    }
    if (f.group) out << " Group " << quoted(*f.group);
    if (o.copy_of >= 0) {
      out << "\n";
      return;
    }
    out << " {\n";
    if (o.light) {
      write_light(*o.light, pad + "  ", out);
    } else if (o.kind == ObjectKind::Pure) {
      const Material& m = o.material;
      const float rho = max_component(m.reflectance), e = max_component(m.emission);
      const Vec3 color = written_color(m);
      const float emission = e > 0.0f ? mean_component(m.emission) / mean_component(color) : 0.0f;
      out << pad << "  Reflectivity " << fmt::format("{:.9g}", rho) << " Color " << vec(color)
          << " Emission " << fmt::format("{:.9g}", emission) << "\n";
      out << pad << "  Data {\n";
      for (const auto& t : o.triangles) {
        out << pad << "    " << vec(t[0]) << ' ' << vec(t[1]) << ' ' << vec(t[2]) << '\n';
      }
      out << pad << "  }\n";
    } else {
      for (int32_t c : o.children) self(self, c, depth + 1);
    }
    out << pad << "}\n";
  };
  out << quoted(scene.name) << '\n';
  for (int32_t r : scene.roots) write(write, r, 0);
}

}  // namespace rad
