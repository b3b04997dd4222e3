// libFuzzer target: any bytes as a Wavefront OBJ file, the part after a line "#MTL" as its
// material library. Every input must end in a model or in one rad::Error. Textures are looked
// for in a folder of small images written once at start (odd sizes, with and without alpha,
// PNG and JPEG, whole and truncated), so an input naming them (map_Kd, map_d, map_Ke: leaf.png,
// leaf_alpha.png, glow.jpg, truncated.png, truncated.jpg) decodes them and reaches the cut-out
// path.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "scene/obj_reader.h"

namespace {

void append(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

// The folder of images, made on the first call.
const std::string& texture_folder() {
  static const std::string folder = [] {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("rad_obj_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::vector<unsigned char> rgba, grey, rgb;
    for (int y = 0; y < 5; ++y) {
      for (int x = 0; x < 3; ++x) {
        rgba.insert(rgba.end(),
                    {uint8_t(x * 90), uint8_t(y * 60), 128, uint8_t((x + y) % 2 * 255)});
        grey.push_back(uint8_t((x + y) % 2 * 255));
      }
    }
    for (int i = 0; i < 7 * 3; ++i) rgb.insert(rgb.end(), {uint8_t(i * 12), 200, uint8_t(255 - i)});
    std::string leaf, alpha, glow;
    stbi_write_png_to_func(append, &leaf, 3, 5, 4, rgba.data(), 3 * 4);
    stbi_write_png_to_func(append, &alpha, 3, 5, 1, grey.data(), 3);
    stbi_write_jpg_to_func(append, &glow, 7, 3, 3, rgb.data(), 90);
    auto write = [&](const char* name, const std::string& bytes) {
      std::ofstream(dir / name, std::ios::binary) << bytes;
    };
    write("leaf.png", leaf);
    write("leaf_alpha.png", alpha);
    write("glow.jpg", glow);
    write("truncated.png", leaf.substr(0, leaf.size() / 2));
    write("truncated.jpg", glow.substr(0, glow.size() / 2));
    return dir.string();
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const size_t split = text.find("#MTL\n");
  try {
    const rad::Model m =
        split == std::string_view::npos
            ? rad::parse_obj_text(std::string(text), "", "fuzz.obj", texture_folder())
            : rad::parse_obj_text(std::string(text.substr(0, split)), text.substr(split + 5),
                                  "fuzz.obj", texture_folder());
    (void)m;
  } catch (const rad::Error&) {
  }
  return 0;
}
