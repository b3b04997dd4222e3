// libFuzzer target: any bytes as an IES LM-63 photometric file, read and then looked up in a few
// directions. Every input must end in a table or in one rad::Error.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "scene/ies_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const rad::Photometry p = rad::parse_ies(text, "fuzz.ies");
    float sum = 0.0f;
    for (float gamma : {0.0f, 12.5f, 90.0f, 179.0f, 180.0f}) {
      for (float c : {-30.0f, 0.0f, 45.0f, 135.0f, 270.0f, 359.9f, 1e9f})
        sum += p.candela_at(gamma, c);
    }
    (void)sum;
  } catch (const rad::Error&) {
  }
  return 0;
}
