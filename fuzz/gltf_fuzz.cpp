// libFuzzer target: any bytes as a glTF file (JSON .gltf or binary .glb), no folder for
// external files. Every input must end in a model or in one rad::Error.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "scene/gltf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const rad::Model m = rad::parse_gltf(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.gltf", "");
    (void)m;
  } catch (const rad::Error&) {
  }
  return 0;
}
