#include "export/image_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>
#include <tinyexr.h>

namespace rad {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::path(RAD_BINARY_DIR) / "test_out" / "image_file";
  fs::create_directories(d);
  return d;
}

/// A 7 x 5 gradient with values from 0 to about 3 (so tone curves matter), distinct per pixel.
Image gradient() {
  Image img(7, 5);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      img.at(x, y) = Vec3(0.4f * float(x), 0.5f * float(y), 0.05f * float(x + 7 * y) + 0.01f);
    }
  }
  return img;
}

TEST(ImageFile, PngHoldsToneMappedSrgbBytes) {
  const Image img = gradient();
  for (ToneCurve curve : {ToneCurve::Clamp, ToneCurve::Reinhard, ToneCurve::Aces}) {
    const ToneMap tm{0.8f, curve};
    const std::string path = (temp_dir() / "gradient.png").string();
    write_image_file(path, img, tm);
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr) << stbi_failure_reason();
    ASSERT_EQ(w, img.width);
    ASSERT_EQ(h, img.height);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        uint8_t want[3];
        to_srgb8(img.at(x, y), tm, want);
        for (int k = 0; k < 3; ++k) {
          EXPECT_EQ(data[3 * (y * w + x) + k], want[k]) << x << "," << y << " channel " << k;
        }
      }
    }
    stbi_image_free(data);
  }
}

TEST(ImageFile, HdrHoldsLinearValuesWithinRgbePrecision) {
  const Image img = gradient();
  const std::string path = (temp_dir() / "gradient.hdr").string();
  write_image_file(path, img, ToneMap{100.0f, ToneCurve::Clamp});  // no exposure in HDR
  int w = 0, h = 0, n = 0;
  float* data = stbi_loadf(path.c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr) << stbi_failure_reason();
  ASSERT_EQ(w, img.width);
  ASSERT_EQ(h, img.height);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Vec3 v = img.at(x, y);
      for (int k = 0; k < 3; ++k) {
        // RGBE shares one exponent: 8 mantissa bits relative to the largest channel.
        EXPECT_NEAR(data[3 * (y * w + x) + k], v[k], max_component(v) / 128.0f) << x << "," << y;
      }
    }
  }
  stbi_image_free(data);
}

TEST(ImageFile, ExrHoldsExactLinearFloats) {
  const Image img = gradient();
  const std::string path = (temp_dir() / "gradient.exr").string();
  write_image_file(path, img, ToneMap{100.0f, ToneCurve::Aces});
  float* rgba = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  ASSERT_EQ(LoadEXR(&rgba, &w, &h, path.c_str(), &err), TINYEXR_SUCCESS) << (err ? err : "");
  ASSERT_EQ(w, img.width);
  ASSERT_EQ(h, img.height);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(rgba[4 * (y * w + x) + k], img.at(x, y)[k]);
    }
  }
  std::free(rgba);
}

TEST(ImageFile, AlphaIsPngsFourthChannelAndExrsAWithTheColourPremultipliedThereOnly) {
  Image img = gradient();
  img.alpha.resize(img.pixels.size());
  for (size_t i = 0; i < img.alpha.size(); ++i) {
    img.alpha[i] = float(i % 5) / 4.0f;
    img.pixels[i] *= img.alpha[i];  // premultiplied, as rendered
  }
  const ToneMap tm{0.8f, ToneCurve::Clamp};
  const std::string png = (temp_dir() / "alpha.png").string();
  write_image_file(png, img, tm);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(png.c_str(), &w, &h, &n, 0);
  ASSERT_NE(data, nullptr) << stbi_failure_reason();
  ASSERT_EQ(n, 4);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const float a = img.alpha[i];
    EXPECT_EQ(data[4 * i + 3], uint8_t(std::lround(a * 255.0f))) << i;
    uint8_t want[3];
    to_srgb8(a > 0.0f ? img.pixels[i] / a : Vec3(0.0f), tm, want);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(data[4 * i + size_t(k)], want[k]) << i;
  }
  stbi_image_free(data);

  const std::string exr = (temp_dir() / "alpha.exr").string();
  write_image_file(exr, img, tm);
  float* rgba = nullptr;
  const char* err = nullptr;
  ASSERT_EQ(LoadEXR(&rgba, &w, &h, exr.c_str(), &err), TINYEXR_SUCCESS) << (err ? err : "");
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(rgba[4 * i + size_t(k)], img.pixels[i][k]);
    EXPECT_EQ(rgba[4 * i + 3], img.alpha[i]);
  }
  std::free(rgba);
}

TEST(ImageFile, PfmHoldsExactLinearFloatsBottomRowFirst) {
  const Image img = gradient();
  const std::string path = (temp_dir() / "gradient.pfm").string();
  write_image_file(path, img, ToneMap{});
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int w = 0, h = 0;
  float scale = 0;
  in >> magic >> w >> h >> scale;
  in.get();  // the single whitespace before the raster
  ASSERT_EQ(magic, "PF");
  ASSERT_EQ(w, img.width);
  ASSERT_EQ(h, img.height);
  ASSERT_LT(scale, 0.0f);  // little-endian
  std::vector<float> data(size_t(w * h * 3));
  in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
  ASSERT_TRUE(in);
  EXPECT_EQ(in.peek(), std::char_traits<char>::eof());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(data[size_t(3 * ((h - 1 - y) * w + x) + k)], img.at(x, y)[k]);
      }
    }
  }
}

TEST(ImageFile, RejectsUnknownExtensionsBeforeWritingAnything) {
  EXPECT_NO_THROW(check_image_extension("a/b.PNG"));
  EXPECT_NO_THROW(check_image_extension("x.exr"));
  EXPECT_THROW(check_image_extension("x.jpg"), Error);
  EXPECT_THROW(check_image_extension("noext"), Error);
  const fs::path p = temp_dir() / "picture.tiff";
  EXPECT_THROW(write_image_file(p.string(), gradient(), ToneMap{}), Error);
  EXPECT_FALSE(fs::exists(p));
}

TEST(ImageFile, LeavesNoTemporaryFiles) {
  const fs::path d = temp_dir() / "atomic";
  fs::remove_all(d);
  fs::create_directories(d);
  for (const char* name : {"a.png", "a.hdr", "a.exr", "a.pfm"}) {
    write_image_file((d / name).string(), gradient(), ToneMap{});
  }
  int files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    ++files;
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
  }
  EXPECT_EQ(files, 4);
}

}  // namespace
}  // namespace rad
