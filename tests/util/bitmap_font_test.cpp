// The built-in 5×7 font: the promised characters exist and differ, sizes follow the formula,
// drawing sets exactly the glyph's pixels and clips at the image edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <bitset>
#include <cstring>

#include "util/bitmap_font.h"

namespace shadowlab {
namespace {

const std::string kCharset = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ :=,.-_+/()?";

int set_bits(char c) {
  int n = 0;
  for (int r = 0; r < kGlyphHeight; ++r) n += int(std::bitset<8>(glyph_rows(c)[r]).count());
  return n;
}

TEST(BitmapFont, CoversDigitsLettersAndSymbolsWithDistinctGlyphs) {
  for (char c : kCharset) {
    EXPECT_TRUE(has_glyph(c)) << c;
    for (int r = 0; r < kGlyphHeight; ++r) EXPECT_LT(glyph_rows(c)[r], 32) << c;  // 5 columns
    if (c != ' ') {
      EXPECT_GT(set_bits(c), 0) << c;
    }
  }
  // No two characters share a bitmap (catches a copy-pasted row table).
  for (size_t i = 0; i < kCharset.size(); ++i)
    for (size_t j = i + 1; j < kCharset.size(); ++j)
      EXPECT_NE(std::memcmp(glyph_rows(kCharset[i]), glyph_rows(kCharset[j]), kGlyphHeight), 0)
          << kCharset[i] << " vs " << kCharset[j];
}

TEST(BitmapFont, LowercaseIsUppercaseAndUnknownIsQuestionMark) {
  EXPECT_EQ(glyph_rows('a'), glyph_rows('A'));
  EXPECT_EQ(glyph_rows('z'), glyph_rows('Z'));
  EXPECT_FALSE(has_glyph('#'));
  EXPECT_EQ(glyph_rows('#'), glyph_rows('?'));
  EXPECT_EQ(glyph_rows('\xe9'), glyph_rows('?'));
}

TEST(BitmapFont, TextSizeFormula) {
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_EQ(text_width("A", 1), 5);
  EXPECT_EQ(text_width("AB", 1), 11);   // 5 + 1 space + 5
  EXPECT_EQ(text_width("512", 2), 34);  // 3 × 6 × 2 − 2
  EXPECT_EQ(text_height(3), 21);
}

TEST(BitmapFont, DrawSetsScaledGlyphPixelsOnly) {
  ImageF img(40, 20, 1, 0.5f);
  draw_text(img, 3, 2, "R1", 2, 1.0f);
  // Each font pixel becomes a 2×2 block; nothing else changes.
  const long lit = std::count(img.data.begin(), img.data.end(), 1.0f);
  EXPECT_EQ(lit, 4L * (set_bits('R') + set_bits('1')));
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y) == 1.0f) {
        EXPECT_GE(x, 3);
        EXPECT_LT(x, 3 + text_width("R1", 2));
        EXPECT_GE(y, 2);
        EXPECT_LT(y, 2 + text_height(2));
      }
  // 'R' row 0 is 0x1E: columns 0..3 set, column 4 clear.
  EXPECT_EQ(img.at(3, 2), 1.0f);
  EXPECT_EQ(img.at(3 + 7, 2), 1.0f);
  EXPECT_EQ(img.at(3 + 8, 2), 0.5f);
}

TEST(BitmapFont, DrawClipsAtTheEdges) {
  ImageF img(6, 5, 1, 0.0f);
  draw_text(img, -3, -4, "8888", 1, 1.0f);  // mostly outside: must not write out of bounds
  draw_text(img, 4, 3, "W", 3, 1.0f);
  const long lit = std::count(img.data.begin(), img.data.end(), 1.0f);
  EXPECT_GT(lit, 0);
  EXPECT_LT(lit, 30);
}

}  // namespace
}  // namespace shadowlab
