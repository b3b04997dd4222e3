#include "export/ply_writer.h"

#include <fmt/format.h>

#include <bit>
#include <cstring>
#include <string>

namespace rad {

namespace {
template <typename T>
void put(std::ostream& out, T v) {
  static_assert(std::endian::native == std::endian::little, "PLY writer assumes little-endian");
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.write(b, sizeof(T));
}
}  // namespace

void write_ply(std::ostream& out, const OutputMesh& m, const ToneMap& tm, bool ascii) {
  const bool uv = !m.uv().empty();
  const size_t groups = m.group_radiosity.size();
  std::string group_header;
  for (size_t g = 0; g < groups; ++g) {
    group_header += fmt::format(
        "property float group{0}_r\nproperty float group{0}_g\n"
        "property float group{0}_b\n",
        g);
  }
  out << "ply\n"
      << (ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n")
      << "comment rad radiosity: rgb = display colour (sRGB), radiosity_* = linear radiosity B, "
         "irradiance_* = the light arriving H (B = E + rho H; lux with photometric lights)\n";
  for (size_t g = 0; g < groups; ++g) {
    out << "comment light group " << g << " \"" << m.group_names[g]
        << "\": groupN_* = linear radiosity B of that group's light alone\n";
  }
  out << "element vertex " << m.position().size() << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n"
      << "property float irradiance_r\nproperty float irradiance_g\nproperty float irradiance_b\n"
      << group_header << (uv ? "property float s\nproperty float t\n" : "") << "element face "
      << m.face_count() << "\n"
      << "property list uchar uint vertex_indices\n"
      << "end_header\n";
  for (size_t v = 0; v < m.position().size(); ++v) {
    uint8_t c[3];
    to_srgb8(m.display[v], tm, c);
    const Vec3 &p = m.position()[v], &b = m.radiosity[v];
    const Vec3 h = v < m.irradiance.size() ? m.irradiance[v] : Vec3(0.0f);
    if (ascii) {
      out << fmt::format("{} {} {} {} {} {} {} {} {} {} {} {}", p.x, p.y, p.z, c[0], c[1], c[2],
                         b.x, b.y, b.z, h.x, h.y, h.z);
    } else {
      put(out, p.x), put(out, p.y), put(out, p.z);
      put(out, c[0]), put(out, c[1]), put(out, c[2]);
      put(out, b.x), put(out, b.y), put(out, b.z);
      put(out, h.x), put(out, h.y), put(out, h.z);
    }
    for (size_t g = 0; g < groups; ++g) {
      const Vec3& bg = m.group_radiosity[g][v];
      if (ascii) {
        out << fmt::format(" {} {} {}", bg.x, bg.y, bg.z);
      } else {
        put(out, bg.x), put(out, bg.y), put(out, bg.z);
      }
    }
    if (uv) {
      // s, t as OBJ's vt and Blender's PLY reader take them: t up the image.
      const Vec2 st(m.uv()[v].x, 1.0f - m.uv()[v].y);
      if (ascii) {
        out << fmt::format(" {} {}", st.x, st.y);
      } else {
        put(out, st.x), put(out, st.y);
      }
    }
    if (ascii) out << '\n';
  }
  for (size_t f = 0; f < m.face_count(); ++f) {
    const uint32_t* i = &m.indices()[3 * f];
    if (ascii) {
      out << fmt::format("3 {} {} {}\n", i[0], i[1], i[2]);
    } else {
      put(out, uint8_t(3)), put(out, i[0]), put(out, i[1]), put(out, i[2]);
    }
  }
}

}  // namespace rad
