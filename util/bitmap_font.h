#pragma once
// A tiny built-in 5×7 bitmap font for labelling images (contact sheets) without a font file.
// Covers 0-9, A-Z (lowercase is drawn as uppercase), space and : = , . - _ + / ( ) ?; any other
// character is drawn as '?'.
#include <cstdint>
#include <string>

#include "core/image.h"

namespace shadowlab {

constexpr int kGlyphWidth = 5;    // glyph cells, font pixels
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // glyph width + 1 column of spacing, font pixels

// The 7 rows of c's glyph, top first; bit 4 is the leftmost column.
const uint8_t* glyph_rows(char c);
// True when c has its own glyph (after mapping lowercase to uppercase).
bool has_glyph(char c);

// Size in image pixels of text drawn at an integer scale (each font pixel is scale × scale):
// width = n × 6 × scale − scale (no trailing spacing), 0 for empty text; height = 7 × scale.
int text_width(const std::string& text, int scale);
int text_height(int scale);

// Draws text into channel 0 of image with its top-left corner at (x, y), setting the glyphs'
// pixels to value; pixels outside the image are clipped. Other pixels are left unchanged.
void draw_text(ImageF& image, int x, int y, const std::string& text, int scale, float value);

}  // namespace shadowlab
