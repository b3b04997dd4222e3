#include "scene/texture_mean.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_HDR
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

#include <cmath>
#include <cstdint>

namespace rad {

namespace {

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

constexpr double kMaxPixels = 64e6;

std::optional<Vec3> mean_of(unsigned char* pixels, int w, int h) {
  if (!pixels) return std::nullopt;
  double lut[256];
  for (int i = 0; i < 256; ++i) lut[i] = srgb_to_linear(i / 255.0);
  double sum[3] = {0, 0, 0};
  const size_t n = size_t(w) * size_t(h);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) sum[c] += lut[pixels[3 * i + size_t(c)]];
  }
  stbi_image_free(pixels);
  return Vec3(float(sum[0] / double(n)), float(sum[1] / double(n)), float(sum[2] / double(n)));
}

}  // namespace

std::optional<Vec3> mean_texture_colour(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  if (!stbi_info(path.c_str(), &w, &h, &channels) || w <= 0 || h <= 0 ||
      double(w) * double(h) > kMaxPixels) {
    return std::nullopt;
  }
  return mean_of(stbi_load(path.c_str(), &w, &h, &channels, 3), w, h);
}

std::optional<Vec3> mean_texture_colour(const unsigned char* bytes, size_t size) {
  int w = 0, h = 0, channels = 0;
  if (size > size_t(INT32_MAX) || !stbi_info_from_memory(bytes, int(size), &w, &h, &channels) ||
      w <= 0 || h <= 0 || double(w) * double(h) > kMaxPixels) {
    return std::nullopt;
  }
  return mean_of(stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 3), w, h);
}

}  // namespace rad
