#include "scene/texture.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_HDR
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

namespace rad {

namespace {

float srgb_to_linear(double c) {
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

constexpr double kMaxPixels = 64e6;

// Each texel of the next level: the mean of the 2x2 (at an odd edge, 2x1 or 1x1) below it.
TextureImage::Level halve(const TextureImage::Level& l) {
  TextureImage::Level n;
  n.width = std::max(1, (l.width + 1) / 2);
  n.height = std::max(1, (l.height + 1) / 2);
  n.texels.resize(size_t(n.width) * size_t(n.height));
  for (int y = 0; y < n.height; ++y) {
    for (int x = 0; x < n.width; ++x) {
      Vec4 sum(0.0f);
      int count = 0;
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          const int sx = 2 * x + dx, sy = 2 * y + dy;
          if (sx >= l.width || sy >= l.height) continue;
          sum += l.texels[size_t(sy) * size_t(l.width) + size_t(sx)];
          ++count;
        }
      }
      n.texels[size_t(y) * size_t(n.width) + size_t(x)] = sum / float(count);
    }
  }
  return n;
}

std::shared_ptr<TextureImage> make_image(unsigned char* pixels, int w, int h, std::string name) {
  if (!pixels) return nullptr;
  auto image = texture_from_pixels(pixels, w, h, std::move(name));
  stbi_image_free(pixels);
  return image;
}

// Texel index i of a row or column of n texels, wrapped.
int wrap(int i, int n, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::ClampToEdge:
      return std::clamp(i, 0, n - 1);
    case TextureWrap::MirroredRepeat: {
      const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat:
    default:
      return ((i % n) + n) % n;
  }
}

// A coordinate brought near [0, 1] so that texel indices stay small integers: repeats by
// whole periods (two for a mirror), clamps a clamped one. Non-finite reads as 0.
double reduce(float c, TextureWrap mode) {
  const double x = std::isfinite(c) ? double(c) : 0.0;
  switch (mode) {
    case TextureWrap::ClampToEdge:
      return std::clamp(x, -1.0, 2.0);
    case TextureWrap::MirroredRepeat:
      return x - 2.0 * std::floor(x * 0.5);
    case TextureWrap::Repeat:
    default:
      return x - std::floor(x);
  }
}

Vec4 texel(const TextureImage::Level& l, int x, int y, const TextureSampler& s) {
  x = wrap(x, l.width, s.wrap_s);
  y = wrap(y, l.height, s.wrap_t);
  return l.texels[size_t(y) * size_t(l.width) + size_t(x)];
}

Vec4 bilinear(const TextureImage::Level& l, double u, double v, const TextureSampler& s) {
  const double x = u * l.width - 0.5, y = v * l.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const int x0 = int(fx), y0 = int(fy);
  const float ax = float(x - fx), ay = float(y - fy);
  const Vec4 top = texel(l, x0, y0, s) * (1.0f - ax) + texel(l, x0 + 1, y0, s) * ax;
  const Vec4 bottom = texel(l, x0, y0 + 1, s) * (1.0f - ax) + texel(l, x0 + 1, y0 + 1, s) * ax;
  return top * (1.0f - ay) + bottom * ay;
}

}  // namespace

namespace {

// stb_image 2.27 (Debian's) trusts the 16 code counts of a JPEG Huffman table (DHT) to sum to
// at most 256 and writes past its tables when they do not (fuzzing found it; stb 2.28 checks).
// False for a JPEG with such a table, which is no valid JPEG; true for anything else.
bool jpeg_tables_fit(const unsigned char* b, size_t n) {
  if (n < 2 || b[0] != 0xFF || b[1] != 0xD8) return true;
  for (size_t i = 2; i + 4 <= n;) {
    const unsigned char m = b[i + 1];
    // Entropy-coded data, fill bytes, stuffed zeros and restart markers carry no length.
    if (b[i] != 0xFF || m == 0xFF) {
      ++i;
      continue;
    }
    if (m == 0x00 || m == 0x01 || (m >= 0xD0 && m <= 0xD7)) {
      i += 2;
      continue;
    }
    if (m == 0xD9) break;  // end of image
    const size_t length = size_t(b[i + 2]) << 8 | b[i + 3];
    if (m == 0xC4) {
      const size_t end = std::min(n, i + 2 + length);
      // A table cut short by the end of the file: stb reads the counts that are there.
      for (size_t at = i + 4; at < end;) {
        size_t codes = 0;
        for (size_t k = 1; k <= 16 && at + k < n; ++k) codes += b[at + k];
        if (codes > 256) return false;
        at += 17 + codes;
      }
    }
    i += 2 + length;
  }
  return true;
}

// stb_image 2.27 grows its buffer for a PNG's image data to what each IDAT chunk's length says
// before reading it: a few bytes claiming a 1.4 GB chunk allocate 1.4 GB (fuzzing found it).
// False for a PNG with a chunk longer than the bytes left, which is no valid PNG (a truncated
// one); true for anything else.
bool png_chunks_fit(const unsigned char* b, size_t n) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (n < 8 || std::memcmp(b, kSignature, 8) != 0) return true;
  for (size_t i = 8; i + 8 <= n;) {
    const size_t length =
        size_t(b[i]) << 24 | size_t(b[i + 1]) << 16 | size_t(b[i + 2]) << 8 | size_t(b[i + 3]);
    if (length > n - i - 8) return false;  // its data, before its 4-byte CRC, past the end
    if (std::memcmp(b + i + 4, "IEND", 4) == 0) break;
    i += 12 + length;
  }
  return true;
}

}  // namespace

std::shared_ptr<TextureImage> texture_from_pixels(const unsigned char* rgba, int w, int h,
                                                  std::string name) {
  auto image = std::make_shared<TextureImage>();
  image->name = std::move(name);
  image->file_width = w, image->file_height = h;
  float lut[256];
  for (int i = 0; i < 256; ++i) lut[i] = srgb_to_linear(i / 255.0);
  TextureImage::Level base;
  base.width = w, base.height = h;
  base.texels.resize(size_t(w) * size_t(h));
  DVec3 sum(0.0);
  for (size_t i = 0; i < base.texels.size(); ++i) {
    const unsigned char* p = rgba + 4 * i;
    const Vec4 t(lut[p[0]], lut[p[1]], lut[p[2]], float(p[3]) / 255.0f);
    base.texels[i] = t;
    image->has_alpha |= p[3] != 255;
    sum += DVec3(t.x, t.y, t.z);
  }
  image->mean = Vec3(sum / double(base.texels.size()));
  while (base.texels.size() > kMaxTextureTexels) base = halve(base);
  image->levels.push_back(std::move(base));
  while (image->levels.back().width > 1 || image->levels.back().height > 1)
    image->levels.push_back(halve(image->levels.back()));
  return image;
}

std::shared_ptr<TextureImage> decode_texture(const unsigned char* bytes, size_t size,
                                             std::string name) {
  int w = 0, h = 0, channels = 0;
  if (size > size_t(INT32_MAX) || !jpeg_tables_fit(bytes, size) || !png_chunks_fit(bytes, size) ||
      !stbi_info_from_memory(bytes, int(size), &w, &h, &channels) || w <= 0 || h <= 0 ||
      double(w) * double(h) > kMaxPixels) {
    return nullptr;
  }
  return make_image(stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4), w, h,
                    std::move(name));
}

std::shared_ptr<TextureImage> read_texture_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return nullptr;
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return nullptr;
  return decode_texture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), path);
}

bool opaque_at(const AlphaMask& m, Vec2 uv) {
  const Vec4 s = sample_texture(m.texture, uv, 0.0f);
  return (m.from_red ? s.x : s.w) * m.scale >= m.cutoff;
}

float opaque_fraction(const AlphaMask& m, Vec2 uv, float width) {
  const TextureImage& image = *m.texture.image;
  const float w = std::isfinite(width)
                      ? std::min(width, float(std::max(image.width(), image.height())))
                      : float(std::max(image.width(), image.height()));
  const Vec2 step(w / float(image.width()), w / float(image.height()));
  int opaque = 0;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const Vec2 at =
          uv + step * Vec2((float(i) + 0.5f) / 4.0f - 0.5f, (float(j) + 0.5f) / 4.0f - 0.5f);
      opaque += opaque_at(m, at);
    }
  }
  return float(opaque) / 16.0f;
}

Vec4 sample_texture(const TextureMap& t, Vec2 uv, float width) {
  const TextureImage& image = *t.image;
  const TextureSampler& s = t.sampler;
  const double u = reduce(uv.x, s.wrap_s), v = reduce(uv.y, s.wrap_t);
  const int last = int(image.levels.size()) - 1;
  // NaN reads as a point, an infinite footprint as the whole image.
  const float level = !(width > 1.0f)        ? 0.0f
                      : std::isfinite(width) ? std::log2(width)
                                             : float(last);
  if (level <= 0.0f) {
    const TextureImage::Level& l = image.levels.front();
    if (s.nearest) {
      return texel(l, int(std::floor(u * l.width)), int(std::floor(v * l.height)), s);
    }
    return bilinear(l, u, v, s);
  }
  if (level >= float(last)) return bilinear(image.levels.back(), u, v, s);
  const int l0 = int(level);
  const float f = level - float(l0);
  return bilinear(image.levels[size_t(l0)], u, v, s) * (1.0f - f) +
         bilinear(image.levels[size_t(l0) + 1], u, v, s) * f;
}

}  // namespace rad
