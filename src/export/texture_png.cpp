#include "export/texture_png.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "export/tonemap.h"

// Its own static copy: image_file.cpp keeps its stb_image_write private the same way.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace rad {

std::string encode_png(const TextureImage& image) {
  const TextureImage::Level& l = image.levels.front();
  const int channels = image.has_alpha ? 4 : 3;
  std::vector<unsigned char> bytes;
  bytes.reserve(l.texels.size() * size_t(channels));
  auto byte = [](float c) { return static_cast<unsigned char>(std::lround(c * 255.0f)); };
  for (const Vec4& t : l.texels) {
    for (int k = 0; k < 3; ++k) bytes.push_back(byte(srgb_encode(t[k])));
    if (channels == 4) bytes.push_back(byte(std::clamp(t[3], 0.0f, 1.0f)));
  }
  std::string png;
  const int ok = stbi_write_png_to_func(
      [](void* out, void* data, int size) {
        static_cast<std::string*>(out)->append(static_cast<const char*>(data), size_t(size));
      },
      &png, l.width, l.height, channels, bytes.data(), l.width * channels);
  if (!ok) throw Error("cannot encode texture '" + image.name + "' as PNG");
  return png;
}

}  // namespace rad
