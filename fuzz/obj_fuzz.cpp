// libFuzzer target: any bytes as a Wavefront OBJ file, the part after a line "#MTL" as its
// material library. Every input must end in a model or in one rad::Error.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("#MTL\n");
  try {
    const rad::Model m = split == std::string_view::npos
                             ? rad::parse_obj_text(std::string(text), "", "fuzz.obj")
                             : rad::parse_obj_text(std::string(text.substr(0, split)),
                                                   text.substr(split + 5), "fuzz.obj");
    (void)m;
  } catch (const rad::Error&) {
  }
  return 0;
}
