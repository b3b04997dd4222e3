// A tiny built-in bitmap font for labels drawn into images (the false-colour legend's numbers
// and unit), so that no font library is needed: 5 x 7 glyphs for the digits and the few letters
// and signs a number with its unit needs.
#pragma once

#include <string_view>

#include "export/image.h"

namespace rad {

/// A glyph's size in font pixels, and the advance from one character to the next.
inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

/// Whether the font draws `c`: the digits, '.', '-', '+', '/', ' ' and the letters
/// "cdeklmxM" (enough for 12.5k, 1e-05, lx, cd/m2).
bool has_glyph(char c);

/// Width in image pixels of `text` drawn with each font pixel a `scale` x `scale` square (no
/// spacing after the last character).
int text_width(std::string_view text, int scale);

/// Draws `text` with its top-left corner at (x, y), each font pixel a `scale` x `scale` square
/// of `colour`; what falls outside the image is cut off. A character without a glyph
/// (has_glyph) takes its place blank.
void draw_text(Image& image, int x, int y, std::string_view text, int scale, const Vec3& colour);

}  // namespace rad
