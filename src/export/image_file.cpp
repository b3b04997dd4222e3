#include "export/image_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_extension.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#include <tinyexr.h>

namespace rad {

namespace {

void append_to_stream(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

void write_png(std::ostream& out, const Image& img, const ToneMap& tm, const std::string& path) {
  // With alpha, RGBA as PNG has it: the colour not premultiplied, the coverage in 8 bits.
  const int channels = img.alpha.empty() ? 3 : 4;
  std::vector<uint8_t> rgb(img.pixels.size() * size_t(channels));
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    uint8_t* p = &rgb[size_t(channels) * i];
    if (channels == 3) {
      to_srgb8(img.pixels[i], tm, p);
      continue;
    }
    const float a = std::clamp(img.alpha[i], 0.0f, 1.0f);
    to_srgb8(a > 0.0f ? img.pixels[i] / a : Vec3(0.0f), tm, p);
    p[3] = uint8_t(std::lround(a * 255.0f));
  }
  if (!stbi_write_png_to_func(append_to_stream, &out, img.width, img.height, channels, rgb.data(),
                              img.width * channels)) {
    throw Error(SourceLoc{path}, "PNG encoding failed");
  }
}

void write_hdr(std::ostream& out, const Image& img, const std::string& path) {
  if (!stbi_write_hdr_to_func(append_to_stream, &out, img.width, img.height, 3, &img.pixels[0].x)) {
    throw Error(SourceLoc{path}, "Radiance HDR encoding failed");
  }
}

void write_exr(std::ostream& out, const Image& img, const std::string& path) {
  // OpenEXR readers expect the channels sorted by name: A, B, G, R. Colour premultiplied by
  // alpha, as OpenEXR has it.
  const size_t n = img.pixels.size();
  const bool alpha = !img.alpha.empty();
  const int count = alpha ? 4 : 3;
  std::vector<float> planes[4];
  for (int c = 0; c < count; ++c) planes[c].resize(n);
  const int b = alpha ? 1 : 0;
  for (size_t i = 0; i < n; ++i) {
    if (alpha) planes[0][i] = img.alpha[i];
    planes[b][i] = img.pixels[i].b, planes[b + 1][i] = img.pixels[i].g;
    planes[b + 2][i] = img.pixels[i].r;
  }
  unsigned char* images[4];
  for (int c = 0; c < count; ++c) images[c] = reinterpret_cast<unsigned char*>(planes[c].data());
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = count;
  image.images = images;
  image.width = img.width;
  image.height = img.height;

  EXRHeader header;
  InitEXRHeader(&header);
  EXRChannelInfo channels[4];
  std::memset(channels, 0, sizeof channels);
  int pixel_types[4], requested[4];
  const char* names[4] = {"A", "B", "G", "R"};
  for (int c = 0; c < count; ++c) {
    std::strncpy(channels[c].name, names[c + (alpha ? 0 : 1)], sizeof channels[c].name - 1);
    pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    requested[c] = TINYEXR_PIXELTYPE_FLOAT;
  }
  header.num_channels = count;
  header.channels = channels;
  header.pixel_types = pixel_types;
  header.requested_pixel_types = requested;
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0) {
    const std::string why = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw Error(SourceLoc{path}, "OpenEXR encoding failed: " + why);
  }
  out.write(reinterpret_cast<const char*>(memory), std::streamsize(size));
  std::free(memory);
}

void write_pfm(std::ostream& out, const Image& img) {
  // Portable float map: "PF", size, negative scale = little-endian, rows from the bottom up.
  static_assert(std::endian::native == std::endian::little, "PFM writer assumes little-endian");
  out << "PF\n" << img.width << " " << img.height << "\n-1.0\n";
  for (int y = img.height - 1; y >= 0; --y) {
    out.write(reinterpret_cast<const char*>(&img.at(0, y).x),
              std::streamsize(sizeof(Vec3)) * img.width);
  }
}

}  // namespace

void check_image_extension(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e != ".png" && e != ".hdr" && e != ".exr" && e != ".pfm") {
    throw Error(SourceLoc{path},
                "unknown image format '" + e + "' (expected .png, .hdr, .exr or .pfm)");
  }
}

void write_image_file(const std::string& path, const Image& img, const ToneMap& tm) {
  check_image_extension(path);
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
  const std::string e = lower_extension(path);
  AtomicFile f(path);
  if (e == ".png") {
    write_png(f.stream(), img, tm, path);
  } else if (e == ".hdr") {
    write_hdr(f.stream(), img, path);
  } else if (e == ".exr") {
    write_exr(f.stream(), img, path);
  } else {
    write_pfm(f.stream(), img);
  }
  f.commit();
}

}  // namespace rad
