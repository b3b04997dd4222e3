// libFuzzer target: any bytes as a Geomview OFF file. Every input must end in triangles or in
// one rad::Error.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "scene/off_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const rad::OffTriangles t = rad::parse_off_text(text, "fuzz.off");
    (void)t;
  } catch (const rad::Error&) {
  }
  return 0;
}
