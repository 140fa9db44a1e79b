// The contact sheet: its size follows the layout formula, each cell is exactly the box-filtered
// mask (checked against a brute-force average), and labels only ink the margins.
#include <gtest/gtest.h>

#include <bitset>
#include <random>

#include "core/error.h"
#include "util/bitmap_font.h"
#include "lab/contact_sheet.h"

namespace shadowlab {
namespace {

ImageF random_mask(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  ImageF m(w, h, 1);
  for (float& v : m.data) v = u(rng);
  return m;
}

// Mean of the source pixels of output pixel (x, y) for factor k, cut at the image edge.
double brute_box(const ImageF& m, int k, int x, int y) {
  double sum = 0.0;
  int n = 0;
  for (int sy = k * y; sy < k * y + k; ++sy)
    for (int sx = k * x; sx < k * x + k; ++sx)
      if (sx < m.width && sy < m.height) {
        sum += m.at(sx, sy);
        ++n;
      }
  return sum / n;
}

// Number of set pixels in the glyphs of text at scale 1.
int glyph_pixels(const std::string& text) {
  int n = 0;
  for (char c : text)
    for (int r = 0; r < kGlyphHeight; ++r) n += int(std::bitset<8>(glyph_rows(c)[r]).count());
  return n;
}

ContactSheetStyle small_style() {
  ContactSheetStyle s;
  s.max_cell_width = 32;
  s.font_scale = 2;
  s.padding = 6;
  s.separator = 2;
  return s;
}

TEST(ContactSheet, SizeFollowsTheLayoutFormula) {
  // 102×61 masks, cells at most 64 wide: factor ceil(102/64) = 2, cells ceil(102/2) = 51 ×
  // ceil(61/2) = 31. Widest row label "TSM:PCF=3" is 9 glyphs: 9·6·2 − 2 = 106 px, so
  // left = 6 + 106 + 12 (one glyph advance at scale 2) + 2 (the frame) = 126; top = 6 + 14 + 6
  // = 26. Columns REF + 3.
  ContactSheetStyle style = small_style();
  style.max_cell_width = 64;
  const std::vector<std::string> rows = {"CSM", "TSM:PCF=3"}, cols = {"128", "256", "512"};
  const ImageF m = random_mask(102, 61, 1);
  const std::vector<std::vector<const ImageF*>> cells = {{&m, &m, &m}, {&m, nullptr, &m}};
  const ImageF sheet = contact_sheet(rows, cols, cells, &m, style);
  EXPECT_EQ(sheet.channels, 1);
  EXPECT_EQ(sheet.width, 126 + 4 * 51 + 3 * 2 + 6);
  EXPECT_EQ(sheet.height, 26 + 2 * 31 + 1 * 2 + 6);
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 102, 61, true, style);
  EXPECT_EQ(l.factor, 2);
  EXPECT_EQ(l.cell_width, 51);
  EXPECT_EQ(l.cell_height, 31);
  EXPECT_EQ(l.font_scale, 2);
  EXPECT_EQ(l.left, 126);
  EXPECT_EQ(l.top, 26);
  EXPECT_EQ(l.cell_x(2), 126 + 2 * 53);
  EXPECT_EQ(l.cell_y(1), 26 + 33);
  // Without the reference there is one column fewer.
  const ImageF no_ref = contact_sheet(rows, cols, cells, nullptr, style);
  EXPECT_EQ(no_ref.width, sheet.width - 51 - 2);
  EXPECT_EQ(no_ref.height, sheet.height);
}

// The frame between the row labels and the grid is the separator's width but never more than
// the padding: with separators of 9 and padding 4, left = 4 + 106 + 12 + 4 = 126. The
// separators are drawn in the default dark grey, visible next to a lit (1) and a shadowed (0)
// cell alike.
TEST(ContactSheet, WideSeparatorsKeepTheFrameAtThePaddingAndShowBetweenCells) {
  ContactSheetStyle style = small_style();
  style.max_cell_width = 64;
  style.padding = 4;
  style.separator = 9;
  const std::vector<std::string> rows = {"CSM", "TSM:PCF=3"}, cols = {"1", "2"};
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 40, 30, false, style);
  EXPECT_EQ(l.left, 4 + 106 + 12 + 4);
  const ImageF lit(40, 30, 1, 1.0f), dark(40, 30, 1, 0.0f);
  const std::vector<std::vector<const ImageF*>> cells = {{&lit, &dark}, {&dark, &lit}};
  const ImageF sheet = contact_sheet(rows, cols, cells, nullptr, ContactSheetStyle{});
  const ContactSheetLayout d = contact_sheet_layout(rows, cols, 40, 30, false, ContactSheetStyle{});
  const float gap = sheet.at(d.cell_x(1) - 1, d.cell_y(0) + 5);
  EXPECT_EQ(gap, ContactSheetStyle{}.separator_value);
  EXPECT_GT(gap, 0.1f);
  EXPECT_LT(gap, 0.9f);
}

TEST(ContactSheet, FontShrinksWhenColumnLabelsWouldOverlap) {
  // Cells of ceil(102/4) = 26 px: "1024" at scale 2 is 46 px > 26 + 2, at scale 1 it is 23 px.
  const ContactSheetLayout l = contact_sheet_layout({"TSM:PCF=3"}, {"1024"}, 102, 61, false, small_style());
  EXPECT_EQ(l.cell_width, 26);
  EXPECT_EQ(l.font_scale, 1);
  EXPECT_EQ(l.left, 6 + 53 + 6 + 2);  // one glyph advance at scale 1, the 2 px frame
  EXPECT_EQ(l.top, 6 + 7 + 6);
  EXPECT_EQ(l.width, 67 + 26 + 6);
  // "512" at scale 2 is 34 px: still too wide for 28 → scale 1 too; "64" (22 px) fits at 2.
  EXPECT_EQ(contact_sheet_layout({"A"}, {"512"}, 102, 61, false, small_style()).font_scale, 1);
  EXPECT_EQ(contact_sheet_layout({"A"}, {"64"}, 102, 61, false, small_style()).font_scale, 2);
}

// A column label wider than the space left of its cell's centre starts at the sheet's left
// edge instead of being cut: at scale 1, row label "A" gives left = 6 + 5 + 6 + 2 = 19 and
// cells 10 wide, so "WWWWWWWWWW" (59 px) centred over column 0 would start at 19 − 24 = −5; it
// is drawn from x = 0, where W's left column (rows 0–5 of the glyph) is ink.
TEST(ContactSheet, AColumnLabelWiderThanTheLeftSideStartsAtTheEdge) {
  const std::vector<std::string> rows = {"A"}, cols = {"WWWWWWWWWW", "1", "2", "3", "4"};
  const ImageF m(10, 10, 1, 1.0f);
  const std::vector<std::vector<const ImageF*>> cells = {{&m, &m, &m, &m, &m}};
  const ContactSheetStyle style = small_style();
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 10, 10, false, style);
  ASSERT_EQ(l.font_scale, 1);
  ASSERT_EQ(l.left, 19);
  const ImageF sheet = contact_sheet(rows, cols, cells, nullptr, style);
  for (int r = 0; r < 6; ++r) EXPECT_EQ(sheet.at(0, style.padding + r), style.ink) << r;
  EXPECT_EQ(sheet.at(58, style.padding), style.ink);  // the last W's right column
}

TEST(ContactSheet, DefaultStyleKeepsCellsAtMost256Wide) {
  for (int w : {96, 256, 257, 320, 1024, 1920}) {
    const ContactSheetLayout l = contact_sheet_layout({"A"}, {"1"}, w, 10, false);
    EXPECT_LE(l.cell_width, 256) << w;
    if (w <= 256) {
      EXPECT_EQ(l.factor, 1) << w;
    } else {
      EXPECT_GE(l.cell_width, 129) << w;  // the smallest factor that fits: not over-shrunk
    }
  }
}

TEST(ContactSheet, CellsAreTheBoxDownscaledMasks) {
  const std::vector<std::string> rows = {"CSM", "TSM"}, cols = {"64", "128"};
  const ImageF ref = random_mask(102, 61, 10);
  const ImageF a = random_mask(102, 61, 11), b = random_mask(102, 61, 12),
               c = random_mask(102, 61, 13);
  const std::vector<std::vector<const ImageF*>> cells = {{&a, &b}, {&c, nullptr}};
  const ContactSheetStyle style = small_style();
  const ImageF sheet = contact_sheet(rows, cols, cells, &ref, style);
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 102, 61, true, style);
  const ImageF* expected[2][3] = {{&ref, &a, &b}, {&ref, &c, nullptr}};
  for (int r = 0; r < 2; ++r)
    for (int col = 0; col < 3; ++col)
      for (int y = 0; y < l.cell_height; ++y)
        for (int x = 0; x < l.cell_width; ++x) {
          const float got = sheet.at(l.cell_x(col) + x, l.cell_y(r) + y);
          const ImageF* m = expected[r][col];
          const double want = m ? brute_box(*m, 4, x, y) : 0.5;  // null cell: mid-grey
          ASSERT_NEAR(got, want, 1e-6) << "row " << r << " col " << col << " at " << x << "," << y;
        }
  // Between neighbouring cells and in the frame around the grid: the separator grey; outside
  // the frame: background.
  EXPECT_EQ(sheet.at(l.cell_x(1) - 1, l.cell_y(0) + 3), style.separator_value);
  EXPECT_EQ(sheet.at(l.cell_x(1) + 2, l.cell_y(1) - 1), style.separator_value);
  EXPECT_EQ(sheet.at(l.left - 1, l.cell_y(1)), style.separator_value);
  EXPECT_EQ(sheet.at(l.left - l.separator - 1, l.cell_y(1) + 1), style.background);
  EXPECT_EQ(sheet.at(sheet.width - 1, sheet.height - 1), style.background);
  EXPECT_EQ(sheet.at(l.cell_x(2) + l.cell_width, l.cell_y(1) + l.cell_height), style.separator_value);
}

TEST(ContactSheet, BoxDownscaleByOneIsIdentityAndAveragesPartialBlocks) {
  const ImageF m = random_mask(7, 5, 3);
  EXPECT_EQ(box_downscale(m, 1).data, m.data);
  ImageF ramp(5, 1, 1);
  for (int x = 0; x < 5; ++x) ramp.at(x, 0) = float(x);
  const ImageF half = box_downscale(ramp, 2);
  ASSERT_EQ(half.width, 3);
  ASSERT_EQ(half.height, 1);  // ceil(1 / 2)
  const ImageF m3 = box_downscale(m, 3);  // 7 × 5 → ceil(7/3) × ceil(5/3)
  EXPECT_EQ(m3.width, 3);
  EXPECT_EQ(m3.height, 2);
  EXPECT_FLOAT_EQ(half.at(0, 0), 0.5f);
  EXPECT_FLOAT_EQ(half.at(1, 0), 2.5f);
  EXPECT_FLOAT_EQ(half.at(2, 0), 4.0f);  // the lone edge pixel, not (4 + 0) / 2
}

TEST(ContactSheet, LabelsInkOnlyTheMargins) {
  // Cells of 0.6 and a null (0.5) cell: any pixel darker than 0.1 is label ink.
  const std::vector<std::string> rows = {"CSM", "RT"}, cols = {"32", "1024"};
  ImageF grey(80, 60, 1, 0.6f);
  const std::vector<std::vector<const ImageF*>> cells = {{&grey, &grey}, {&grey, nullptr}};
  const ContactSheetStyle style = small_style();
  const ImageF sheet = contact_sheet(rows, cols, cells, &grey, style);
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 80, 60, true, style);
  std::vector<int> ink_in_row(2, 0), ink_in_col(3, 0);
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x) {
      if (sheet.at(x, y) >= 0.1f) continue;
      ASSERT_TRUE(x < l.left || y < l.top) << "ink inside the grid at " << x << "," << y;
      for (int r = 0; r < 2; ++r)
        if (x < l.left && y >= l.cell_y(r) && y < l.cell_y(r) + l.cell_height) ++ink_in_row[r];
      for (int c = 0; c < 3; ++c)
        if (y < l.top && x >= l.cell_x(c) && x < l.cell_x(c) + l.cell_width) ++ink_in_col[c];
    }
  // Every row and column (REF included) carries exactly its label's glyph pixels, each a
  // font_scale² block (labels here fit their cell, so none spills past the counted span).
  const int s2 = l.font_scale * l.font_scale;
  EXPECT_EQ(ink_in_row[0], s2 * glyph_pixels("CSM"));
  EXPECT_EQ(ink_in_row[1], s2 * glyph_pixels("RT"));
  EXPECT_EQ(ink_in_col[0], s2 * glyph_pixels("REF"));
  EXPECT_EQ(ink_in_col[1], s2 * glyph_pixels("32"));
  EXPECT_EQ(ink_in_col[2], s2 * glyph_pixels("1024"));
  // The top margin above the grid's frame holds only background and ink.
  for (int y = 0; y < l.top - l.separator; ++y)
    for (int x = 0; x < sheet.width; ++x)
      ASSERT_TRUE(sheet.at(x, y) == style.background || sheet.at(x, y) == style.ink) << x << "," << y;
}

TEST(ContactSheet, BadMasksAreInputErrors) {
  const ImageF a(40, 30, 1, 0.5f), b(41, 30, 1, 0.5f), two(40, 30, 2, 0.5f), rgb(40, 30, 3, 0.5f);
  EXPECT_THROW(contact_sheet({"A"}, {"1", "2"}, {{&a, &b}}, nullptr), InputError);
  EXPECT_THROW(contact_sheet({"A"}, {"1"}, {{&a}}, &b), InputError);
  EXPECT_THROW(contact_sheet({"A"}, {"1"}, {{&two}}, nullptr), InputError);  // 1 or 3 channels
  EXPECT_THROW(contact_sheet({"A"}, {"1"}, {{&rgb}}, &a), InputError);       // not mixed
  EXPECT_THROW(contact_sheet({"A"}, {"1"}, {{nullptr}}, nullptr), InputError);
  EXPECT_THROW(contact_sheet({}, {}, {}, nullptr), InputError);
  // Only null cells next to a reference are fine: the reference fixes the size.
  const ImageF ok = contact_sheet({"A"}, {"1"}, {{nullptr}}, &a);
  EXPECT_GT(ok.width, 2 * 40);
}

// The longest row label is followed by background before the first image: in its row, scanning
// right from the label's last ink pixel, at least one glyph advance (6 px at scale 1) of
// background comes before the first pixel that is not background (the grid's frame or a cell).
TEST(ContactSheet, LongestRowLabelKeepsAGapBeforeTheFirstImage) {
  for (const int scale : {1, 2}) {
    ContactSheetStyle style = small_style();
    style.font_scale = scale;
    style.max_cell_width = 64;
    const std::vector<std::string> rows = {"CSM", "TEVSM:MOMENTS=4,BLUR=5"}, cols = {"16"};
    ImageF dark(64, 40, 1, 0.0f);  // a black cell: as dark as the ink, so only the gap tells
    const ImageF sheet = contact_sheet(rows, cols, {{&dark}, {&dark}}, &dark, style);
    const ContactSheetLayout l = contact_sheet_layout(rows, cols, 64, 40, true, style);
    ASSERT_EQ(l.font_scale, scale);
    int worst_gap = 1 << 30;
    for (int y = l.cell_y(1); y < l.cell_y(1) + l.cell_height; ++y) {
      int last_ink = -1;
      for (int x = 0; x < text_width(rows[1], scale) + style.padding; ++x)
        if (sheet.at(x, y) == style.ink) last_ink = x;
      if (last_ink < 0) continue;  // a row of the band the glyphs leave empty
      int x = last_ink + 1;
      while (x < sheet.width && sheet.at(x, y) == style.background) ++x;
      worst_gap = std::min(worst_gap, x - last_ink - 1);
    }
    ASSERT_NE(worst_gap, 1 << 30) << "no label ink found";
    EXPECT_GE(worst_gap, kGlyphAdvance * scale) << "scale " << scale;
  }
}

// Captions: the rows move apart by the caption strip (text height + 2); each caption's glyph
// pixels are inked under its cell and nowhere else; a 3-channel sheet has the 1-channel sheet's
// layout, the cells' colours, and its text in every channel.
TEST(ContactSheet, CaptionsAndShadedCells) {
  const ContactSheetStyle style = small_style();
  const std::vector<std::string> rows = {"A", "B"}, cols = {"1", "2"};
  // 60×30 masks in cells of 30×15 (factor 2): the captions fit their cells at font scale 1.
  const ImageF m = random_mask(60, 30, 3);
  const std::vector<std::vector<const ImageF*>> cells = {{&m, &m}, {&m, &m}};
  const std::vector<std::vector<std::string>> captions = {{"0.5", "0.25"}, {"1", "0.125"}};
  const ContactSheetLayout plain = contact_sheet_layout(rows, cols, 60, 30, true, style);
  const ContactSheetLayout l = contact_sheet_layout(rows, cols, 60, 30, true, style, &captions);
  EXPECT_EQ(l.font_scale, 1);  // "0.125" is 58 px at scale 2, wider than the 30 px cells
  EXPECT_EQ(l.caption, text_height(l.font_scale) + 2);
  EXPECT_EQ(l.height, plain.height - (plain.top - l.top) + 2 * l.caption);
  EXPECT_EQ(l.cell_y(1), l.top + l.cell_height + l.caption + l.separator);
  const ImageF sheet = contact_sheet(rows, cols, cells, &m, style, &captions);
  ASSERT_EQ(sheet.height, l.height);
  const int s = l.font_scale;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      // Ink pixels in the caption strip under cell (r, c): the caption's glyph pixels × s².
      int ink = 0;
      for (int y = l.cell_y(r) + l.cell_height; y < l.cell_y(r) + l.cell_height + l.caption; ++y)
        for (int x = l.cell_x(1 + c); x < l.cell_x(1 + c) + l.cell_width; ++x)
          ink += sheet.at(x, y) == style.ink;
      EXPECT_EQ(ink, glyph_pixels(captions[size_t(r)][size_t(c)]) * s * s) << r << "," << c;
    }
  // The same sheet from 3-channel images whose channels are m, 1 − m and m/2.
  ImageF rgb(60, 30, 3);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 60; ++x) {
      rgb.at(x, y, 0) = m.at(x, y);
      rgb.at(x, y, 1) = 1.0f - m.at(x, y);
      rgb.at(x, y, 2) = 0.5f * m.at(x, y);
    }
  const std::vector<std::vector<const ImageF*>> rgb_cells = {{&rgb, &rgb}, {&rgb, &rgb}};
  const ImageF colour = contact_sheet(rows, cols, rgb_cells, &rgb, style, &captions);
  ASSERT_EQ(colour.channels, 3);
  ASSERT_EQ(colour.width, sheet.width);
  ASSERT_EQ(colour.height, sheet.height);
  const ImageF small = box_downscale(rgb, l.factor);
  for (int y = 0; y < l.cell_height; ++y)
    for (int x = 0; x < l.cell_width; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(colour.at(l.cell_x(2) + x, l.cell_y(1) + y, c), small.at(x, y, c));
  // Text: wherever the grey sheet is ink outside the cells, every channel of the colour one is.
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x)
      if (x < l.left - style.separator || y < l.top - style.separator) {
        for (int c = 0; c < 3; ++c) ASSERT_EQ(colour.at(x, y, c), sheet.at(x, y)) << x << "," << y;
      }
  // Images of mixed channel counts are refused.
  const std::vector<std::vector<const ImageF*>> mixed = {{&m, &rgb}, {&m, &m}};
  EXPECT_THROW(contact_sheet(rows, cols, mixed, &m, style), InputError);
}

}  // namespace
}  // namespace shadowlab
