// libFuzzer target: any bytes as a PLY file (ASCII or binary). Every input must end in a model
// or in one rad::Error; no count in a header may turn into a huge allocation.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "scene/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const rad::Model m =
        rad::parse_ply(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
    (void)m;
  } catch (const rad::Error&) {
  }
  return 0;
}
