#include "export/image_file.h"

#include <algorithm>
#include <bit>
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
  std::vector<uint8_t> rgb(img.pixels.size() * 3);
  for (size_t i = 0; i < img.pixels.size(); ++i) to_srgb8(img.pixels[i], tm, &rgb[3 * i]);
  if (!stbi_write_png_to_func(append_to_stream, &out, img.width, img.height, 3, rgb.data(),
                              img.width * 3)) {
    throw Error(SourceLoc{path}, "PNG encoding failed");
  }
}

void write_hdr(std::ostream& out, const Image& img, const std::string& path) {
  if (!stbi_write_hdr_to_func(append_to_stream, &out, img.width, img.height, 3, &img.pixels[0].x)) {
    throw Error(SourceLoc{path}, "Radiance HDR encoding failed");
  }
}

void write_exr(std::ostream& out, const Image& img, const std::string& path) {
  // OpenEXR readers expect the channels sorted by name: B, G, R.
  const size_t n = img.pixels.size();
  std::vector<float> planes[3];
  for (auto& p : planes) p.resize(n);
  for (size_t i = 0; i < n; ++i) {
    planes[0][i] = img.pixels[i].b, planes[1][i] = img.pixels[i].g, planes[2][i] = img.pixels[i].r;
  }
  unsigned char* images[3] = {reinterpret_cast<unsigned char*>(planes[0].data()),
                              reinterpret_cast<unsigned char*>(planes[1].data()),
                              reinterpret_cast<unsigned char*>(planes[2].data())};
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = 3;
  image.images = images;
  image.width = img.width;
  image.height = img.height;

  EXRHeader header;
  InitEXRHeader(&header);
  EXRChannelInfo channels[3];
  std::memset(channels, 0, sizeof channels);
  int pixel_types[3], requested[3];
  const char* names[3] = {"B", "G", "R"};
  for (int c = 0; c < 3; ++c) {
    std::strncpy(channels[c].name, names[c], sizeof channels[c].name - 1);
    pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    requested[c] = TINYEXR_PIXELTYPE_FLOAT;
  }
  header.num_channels = 3;
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
