// The mean colour of an image, for a material's base texture: radiosity is per vertex, so a
// textured material reflects its texture's mean colour.
#pragma once

#include <optional>
#include <string>

#include "core/math.h"

namespace rad {

/// The mean linear colour of the image at `path` (PNG, JPEG, TGA, BMP, ... via stb_image; 8-bit
/// values taken as sRGB), or nothing when it cannot be read. Images above 64 Mpixel are refused.
std::optional<Vec3> mean_texture_colour(const std::string& path);

/// The same for an encoded image in memory (a glTF buffer's PNG or JPEG).
std::optional<Vec3> mean_texture_colour(const unsigned char* bytes, size_t size);

}  // namespace rad
