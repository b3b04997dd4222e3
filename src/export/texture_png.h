// A texture written back out: level 0 of a decoded image as the PNG a viewer reads.
#pragma once

#include <string>

#include "scene/texture.h"

namespace rad {

/// The image's level 0 as PNG bytes: its linear colour encoded back to 8-bit sRGB (so an 8-bit
/// sRGB file read in comes back with the same bytes), with its alpha when some texel is not
/// opaque. Throws rad::Error naming the image when encoding fails.
std::string encode_png(const TextureImage& image);

}  // namespace rad
