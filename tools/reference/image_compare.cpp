#include "reference/image_compare.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace rad {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(SourceLoc{path, 0, 0}, what);
}

// The header of a PNM-style file: whitespace-separated tokens, then exactly one whitespace
// character before the binary data.
std::string token(std::istream& in) {
  std::string s;
  in >> s;
  return s;
}

int dimension(std::istream& in, const std::string& path) {
  const std::string s = token(in);
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end || v < 1 || v > (1 << 16)) fail(path, "bad image size '" + s + "'");
  return int(v);
}

}  // namespace

FloatImage read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the image");
  const std::string magic = token(in);
  if (magic != "PF" && magic != "Pf") fail(path, "not a PFM file (expected PF or Pf)");
  const int channels = magic == "PF" ? 3 : 1;
  FloatImage img;
  img.width = dimension(in, path);
  img.height = dimension(in, path);
  const std::string scale_text = token(in);
  const double scale = std::strtod(scale_text.c_str(), nullptr);
  if (!(scale != 0.0) || !std::isfinite(scale)) fail(path, "bad PFM scale '" + scale_text + "'");
  in.get();  // the single whitespace before the data
  const bool little = scale < 0.0;
  const size_t row = size_t(img.width) * size_t(channels);
  std::vector<float> data(row * size_t(img.height));
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
  if (!in) fail(path, "the PFM file is truncated");
  if (little != (std::endian::native == std::endian::little)) {
    for (float& f : data) {
      uint32_t u;
      std::memcpy(&u, &f, 4);
      u = (u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) | (u << 24);
      std::memcpy(&f, &u, 4);
    }
  }
  img.pixels.resize(size_t(img.width) * size_t(img.height));
  for (int y = 0; y < img.height; ++y) {
    const float* src = data.data() + size_t(img.height - 1 - y) * row;  // bottom row first
    for (int x = 0; x < img.width; ++x) {
      const float* p = src + size_t(x) * size_t(channels);
      img.pixels[size_t(y) * size_t(img.width) + size_t(x)] =
          channels == 3 ? DVec3(p[0], p[1], p[2]) : DVec3(p[0]);
    }
  }
  return img;
}

void write_pfm(const std::string& path, const FloatImage& img) {
  static_assert(std::endian::native == std::endian::little, "writes little-endian PFM");
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << img.width << " " << img.height << "\n-1.0\n";
  std::vector<float> row(size_t(img.width) * 3);
  for (int y = img.height - 1; y >= 0; --y) {
    for (int x = 0; x < img.width; ++x) {
      const DVec3& p = img.pixels[size_t(y) * size_t(img.width) + size_t(x)];
      row[3 * size_t(x)] = float(p.x), row[3 * size_t(x) + 1] = float(p.y);
      row[3 * size_t(x) + 2] = float(p.z);
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * 4));
  }
  out.close();
  if (!out) fail(path, "cannot write the image");
}

std::vector<uint8_t> read_mask_pgm(const std::string& path, int width, int height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the mask");
  if (token(in) != "P5") fail(path, "not a binary PGM (P5)");
  const int w = dimension(in, path), h = dimension(in, path);
  if (token(in) != "255") fail(path, "expected 8-bit grey (maximum 255)");
  in.get();
  if (w != width || h != height) {
    fail(path, fmt::format("the mask is {}x{}, the images {}x{}", w, h, width, height));
  }
  std::vector<uint8_t> mask(size_t(w) * size_t(h));
  in.read(reinterpret_cast<char*>(mask.data()), std::streamsize(mask.size()));
  if (!in) fail(path, "the mask is truncated");
  for (uint8_t& m : mask) m = m >= 128 ? 1 : 0;
  return mask;
}

void write_mask_pgm(const std::string& path, const std::vector<uint8_t>& mask, int width,
                    int height) {
  std::ofstream out(path, std::ios::binary);
  out << "P5\n" << width << " " << height << "\n255\n";
  for (uint8_t m : mask) out.put(m ? char(255) : char(0));
  out.close();
  if (!out) fail(path, "cannot write the mask");
}

ImageComparison compare_images(const FloatImage& image, const FloatImage& reference,
                               const std::vector<uint8_t>& interior) {
  if (image.width != reference.width || image.height != reference.height) {
    throw Error(fmt::format("the image is {}x{}, the reference {}x{}", image.width, image.height,
                            reference.width, reference.height));
  }
  struct Sums {
    size_t n = 0;
    DVec3 abs{0.0}, diff{0.0}, ref{0.0};
  } in, all;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const DVec3 d = image.pixels[i] - reference.pixels[i];
    for (Sums* s : {&all, &in}) {
      if (s == &in && !(i < interior.size() && interior[i])) continue;
      ++s->n;
      s->abs += glm::abs(d);
      s->diff += d;
      s->ref += reference.pixels[i];
    }
  }
  auto error = [](const Sums& s) {
    ImageError e;
    e.pixels = s.n;
    const DVec3 ref = glm::max(s.ref, DVec3(1e-300));
    e.error = s.abs / ref;
    e.bias = s.diff / ref;
    return e;
  };
  return {error(in), error(all)};
}

std::string format_image_comparison(const ImageComparison& c) {
  auto line = [](const char* name, const ImageError& e) {
    return fmt::format(
        "{:<9} {:>8} pixels: mean relative error {:.3f}% (R {:.3f}% G {:.3f}% B {:.3f}%), "
        "bias {:+.3f}%\n",
        name, e.pixels, 100.0 * e.mean_error(), 100.0 * e.error.x, 100.0 * e.error.y,
        100.0 * e.error.z, 100.0 * e.mean_bias());
  };
  return line("interior", c.interior) + line("all", c.all);
}

}  // namespace rad
