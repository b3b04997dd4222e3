// Linear images for the camera reference: PFM files (as rad writes them), the interior mask,
// and the error of a picture against the reference.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace rad {

/// An RGB float image, rows top first.
struct FloatImage {
  int width = 0, height = 0;
  std::vector<DVec3> pixels;
};

/// Portable float map: "PF", width height, a negative scale (little-endian), rows bottom up, as
/// rad writes .pfm (export/image_file.cpp). Also reads big-endian (positive scale) and
/// grey ("Pf") maps; the scale's magnitude is ignored (rad writes 1). Throws rad::Error.
FloatImage read_pfm(const std::string& path);
void write_pfm(const std::string& path, const FloatImage& img);

/// The interior mask as a binary PGM (P5, 255 = interior, 0 = not), rows top first.
std::vector<uint8_t> read_mask_pgm(const std::string& path, int width, int height);
void write_mask_pgm(const std::string& path, const std::vector<uint8_t>& mask, int width,
                    int height);

/// The error of a picture over a set of pixels, per channel c:
///   error_c = sum over the pixels of |image_c - reference_c| / sum of reference_c,
/// the mean absolute error relative to the reference's mean over those pixels (so a dark pixel
/// weighs as much as its light, not more), and the figure is the mean over the three channels.
/// bias is the same with the signed difference: the part of the error that is the picture
/// being lighter (> 0) or darker overall.
struct ImageError {
  size_t pixels = 0;
  DVec3 error{0.0}, bias{0.0};
  double mean_error() const { return (error.x + error.y + error.z) / 3.0; }
  double mean_bias() const { return (bias.x + bias.y + bias.z) / 3.0; }
};

struct ImageComparison {
  ImageError interior, all;
};

/// Throws rad::Error when the sizes differ.
ImageComparison compare_images(const FloatImage& image, const FloatImage& reference,
                               const std::vector<uint8_t>& interior);

/// Two lines, "interior ..." and "all ...", each with the pixel count, the error and the bias in
/// percent: the format tools/bench reads.
std::string format_image_comparison(const ImageComparison& c);

}  // namespace rad
