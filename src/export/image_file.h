// Writing rendered images: PNG (display-referred, sRGB) or HDR/EXR/PFM (linear), by extension.
#pragma once

#include <string>

#include "export/image.h"
#include "export/tonemap.h"

namespace rad {

/// Throws rad::Error unless the path ends in .png, .hdr, .exr or .pfm (any case); checked before
/// solving so that a bad name costs nothing.
void check_image_extension(const std::string& path);

/// Writes `img` atomically (the file appears complete or not at all), by extension:
///   .png  8-bit sRGB RGB: tone_map(pixel, tm) then the sRGB transfer function; RGBA with
///         the image's alpha (the colour divided by it first: PNG's is not premultiplied);
///   .hdr  Radiance RGBE, .exr  OpenEXR 32-bit float RGB (ZIP), .pfm  little-endian float RGB:
///         the linear pixel values as rendered (scene units; neither exposure nor tone curve,
///         for grading elsewhere). OpenEXR adds the alpha as channel A (the colour stays
///         premultiplied, as OpenEXR has it); .hdr and .pfm have none (the colour over black).
/// Throws rad::Error on a bad extension or a failed write.
void write_image_file(const std::string& path, const Image& img, const ToneMap& tm);

}  // namespace rad
