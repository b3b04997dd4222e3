// The built-in bitmap font: what it draws, how wide, and that it stays inside the image.
#include "export/bitmap_font.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

int lit(const Image& img) {
  int n = 0;
  for (const Vec3& p : img.pixels) n += p != Vec3(0.0f);
  return n;
}

TEST(BitmapFont, HasTheCharactersOfANumberAndItsUnit) {
  for (char c : std::string("0123456789.-+/ cdeklmxM")) EXPECT_TRUE(has_glyph(c)) << c;
  EXPECT_FALSE(has_glyph('Q'));
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_EQ(text_width("8", 1), kGlyphWidth);
  EXPECT_EQ(text_width("12.5k", 2), (5 * kGlyphAdvance - 1) * 2);
}

TEST(BitmapFont, DrawsEachGlyphScaledAndDistinct) {
  Image one(kGlyphWidth, kGlyphHeight), two(2 * kGlyphWidth, 2 * kGlyphHeight);
  draw_text(one, 0, 0, "8", 1, Vec3(1.0f));
  draw_text(two, 0, 0, "8", 2, Vec3(1.0f));
  EXPECT_EQ(lit(one), 17);  // three bars and four uprights of 2
  EXPECT_EQ(lit(two), 4 * lit(one));
  // Every digit is its own picture.
  std::vector<std::vector<Vec3>> seen;
  for (char c : std::string("0123456789")) {
    Image g(kGlyphWidth, kGlyphHeight);
    draw_text(g, 0, 0, std::string(1, c), 1, Vec3(1.0f));
    EXPECT_GT(lit(g), 5) << c;
    for (const auto& other : seen) EXPECT_NE(g.pixels, other) << c;
    seen.push_back(g.pixels);
  }
  // Unknown characters leave their place blank.
  Image blank(20, 10);
  draw_text(blank, 0, 0, "QQQ", 1, Vec3(1.0f));
  EXPECT_EQ(lit(blank), 0);
}

TEST(BitmapFont, TextPartlyOutsideTheImageIsCutOff) {
  Image img(8, 8);
  draw_text(img, -3, -3, "888", 3, Vec3(1.0f));
  draw_text(img, 6, 6, "888", 3, Vec3(1.0f));
  EXPECT_GT(lit(img), 0);
}

}  // namespace
}  // namespace rad
