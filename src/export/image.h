// A linear RGB image: what the rasterizer produces and the image writers consume.
#pragma once

#include <vector>

#include "core/math.h"

namespace rad {

struct Image {
  int width = 0, height = 0;
  std::vector<Vec3> pixels;  // linear RGB, row-major, top row first
  /// Per pixel, the part of it that a surface covers (the colour is premultiplied by it), or
  /// empty: every pixel opaque.
  std::vector<float> alpha;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Vec3(0.0f)) {}
  Vec3& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const Vec3& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

}  // namespace rad
