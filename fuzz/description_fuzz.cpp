// libFuzzer target: any bytes as a scene description, parsed and built into a hierarchy. Every
// input must end in a hierarchy or in one rad::Error; anything else (a crash, a sanitizer
// report, another exception, a leak, a timeout) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "hierarchy/hierarchy.h"
#include "scene/parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Named inside the bundled scenes' folder, so `File "off/..."` finds the bundled OFF files.
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    // Copies of copies may place up to 50M triangles in rad; a fuzzer stays within its memory.
    const rad::BuildLimits limits{2'000'000, 200'000, 256};
    const rad::Hierarchy h = rad::build_hierarchy(
        rad::parse_scene_text(text, RAD_SOURCE_DIR "/scenes/fuzz.des"), limits);
    (void)h;
  } catch (const rad::Error&) {
  }
  return 0;
}
