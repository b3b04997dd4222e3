// A material's texture as the solver samples it: the image decoded once to linear colour and
// alpha with a mip pyramid (so a vertex can take the texture's mean over the element it stands
// for), and the sampler that says how coordinates outside [0, 1] wrap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"

namespace rad {

/// A decoded image: linear RGB (decoded from sRGB) and alpha (stored linear), level 0 then
/// each level half the size of the one before (box-filtered), down to one texel.
struct TextureImage {
  std::string name;  // the file, or "image N of FILE" for one inside a glTF
  struct Level {
    int width = 0, height = 0;
    std::vector<Vec4> texels;  // row 0 at v = 0 (the glTF convention)
  };
  std::vector<Level> levels;
  Vec3 mean{0.0f};  // the mean linear colour over level 0
  /// The size of the file's image; level 0 is that, or its reduction when larger than
  /// kMaxTextureTexels.
  int file_width = 0, file_height = 0;
  bool has_alpha = false;  // some texel is not fully opaque
  int width() const { return levels.front().width; }
  int height() const { return levels.front().height; }
};

/// Level 0 keeps at most this many texels (64 MiB of linear RGBA): larger images are halved
/// until they fit. A radiosity vertex stands for an element of at least scene size / 256, so
/// finer detail than 2048 texels across averages out unless a texture repeats many times.
inline constexpr size_t kMaxTextureTexels = size_t(2048) * 2048;

enum class TextureWrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };

/// How coordinates are read: glTF's sampler (its wrap modes and magnification filter; its
/// minification is what the element filter does).
struct TextureSampler {
  TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
  bool nearest = false;  // magFilter NEAREST: texels show as squares when magnified
};

/// A material's base-colour texture: the image (shared by every material that names it) and
/// this use's sampler. Empty when the material has none.
struct TextureMap {
  std::shared_ptr<const TextureImage> image;
  TextureSampler sampler;
  explicit operator bool() const { return bool(image); }
};

/// Where a material is cut out (glTF alphaMode MASK, BLEND taken as MASK at 0.5; OBJ map_d):
/// where the texture's alpha times `scale` is below `cutoff`, the surface is a hole that light
/// passes through.
struct AlphaMask {
  TextureMap texture;
  bool from_red = false;  // an OBJ map_d image without alpha: its grey level is the alpha
  float scale = 1.0f;     // glTF baseColorFactor's alpha
  float cutoff = 0.5f;
  explicit operator bool() const { return bool(texture); }
};

/// Whether the mask is opaque at `uv`: its level-0 texel there (nearest, or bilinear when the
/// sampler says linear), times the scale, at least the cutoff. The test every visibility backend
/// makes where a shadow ray meets a cut-out triangle.
bool opaque_at(const AlphaMask& m, Vec2 uv);

/// The fraction of a square of `width` level-0 texels centred at `uv` that is opaque, from
/// 4 x 4 opaque_at tests spread over it.
float opaque_fraction(const AlphaMask& m, Vec2 uv, float width);

/// The texture of w x h pixels of 8-bit sRGB colour and linear alpha, row by row from v = 0:
/// what decode_texture makes of an image file's pixels.
std::shared_ptr<TextureImage> texture_from_pixels(const unsigned char* rgba, int w, int h,
                                                  std::string name);

/// Decodes an image file's bytes (whatever stb_image reads: PNG, JPEG, BMP, TGA, ...), or
/// returns nullptr when they are not an image it decodes or hold more than 64 million pixels.
std::shared_ptr<TextureImage> decode_texture(const unsigned char* bytes, size_t size,
                                             std::string name);

/// Reads and decodes an image file; nullptr when it cannot be read or decoded.
std::shared_ptr<TextureImage> read_texture_file(const std::string& path);

/// The texture's linear colour and alpha averaged over a square of `width` level-0 texels
/// centred at `uv` (trilinear between the mip levels; under one texel, the sampler's
/// magnification filter). Coordinates wrap by the sampler; non-finite ones read as 0.
Vec4 sample_texture(const TextureMap& t, Vec2 uv, float width);

}  // namespace rad
