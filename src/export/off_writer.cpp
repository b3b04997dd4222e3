#include "export/off_writer.h"

#include <fmt/format.h>

#include <cstdint>
#include <iterator>

namespace rad {

void write_off(std::ostream& out, const OutputMesh& m, const ToneMap& tm) {
  fmt::memory_buffer b;
  auto it = std::back_inserter(b);
  fmt::format_to(it, "COFF\n{} {} 0\n", m.position().size(), m.face_count());
  for (size_t v = 0; v < m.position().size(); ++v) {
    uint8_t c[3];
    to_srgb8(m.display[v], tm, c);
    const Vec3& p = m.position()[v];
    fmt::format_to(it, "{} {} {} {} {} {} 1\n", p.x, p.y, p.z, float(c[0]) / 255.0f,
                   float(c[1]) / 255.0f, float(c[2]) / 255.0f);
  }
  for (size_t f = 0; f < m.face_count(); ++f) {
    const uint32_t* i = &m.indices()[3 * f];
    fmt::format_to(it, "3 {} {} {}\n", i[0], i[1], i[2]);
  }
  out.write(b.data(), std::streamsize(b.size()));
}

}  // namespace rad
