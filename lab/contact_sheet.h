#pragma once
// A contact sheet of masks laid out like Kluczek's Figure 4: one row per technique, one column
// per resolution (optionally the reference first), each cell a box-downscaled mask, labels in
// the left and top margins drawn with the built-in bitmap font.
#include <string>
#include <vector>

#include "core/image.h"

namespace shadowlab {

// Everything that changes how the sheet looks. Values are grey levels in [0,1] (linear).
struct ContactSheetStyle {
  int max_cell_width = 256;        // px; masks shrink by the smallest integer factor that fits
  int font_scale = 2;              // image px per font px (5×7 glyphs → 10×14)
  int padding = 6;                 // px around the labels and at the right and bottom edges
  int separator = 2;               // px of grey between neighbouring cells and around the grid
  float background = 1.0f;         // margins: white
  float ink = 0.0f;                // label text: black
  float separator_value = 0.25f;   // dark grey: visible next to lit (1) and shadowed (0) cells
  float null_value = 0.5f;         // a cell without a mask: mid-grey
};

// Where everything goes, px. Column 0 is the reference when there is one.
struct ContactSheetLayout {
  int factor = 1;                  // box-downscale factor = ceil(mask width / max_cell_width)
  int cell_width = 0;              // ceil(mask width / factor)
  int cell_height = 0;             // ceil(mask height / factor)
  int font_scale = 1;              // style.font_scale, halved until column labels fit their
                                   // column pitch (cell_width + separator) and captions their
                                   // cell width, or it reaches 1
  int left = 0;                    // padding + widest row label (at font_scale) + one glyph
                                   // advance (6 × font_scale) + the grid's frame
                                   // (min(separator, padding))
  int top = 0;                     // padding + text height (at font_scale) + padding
  int separator = 0;
  int caption = 0;                 // px under each cell for its caption: text height + 2 when
                                   // the sheet has captions, else 0
  int rows = 0, columns = 0;       // columns count the reference column
  int width = 0;                   // left + columns × cell_width + (columns−1) × separator + padding
  int height = 0;                  // top + rows × (cell_height + caption) + (rows−1) × separator
                                   // + padding
  int cell_x(int column) const { return left + column * (cell_width + separator); }
  int cell_y(int row) const { return top + row * (cell_height + caption + separator); }
};

// Layout for masks of mask_width × mask_height px (both >= 1).
ContactSheetLayout contact_sheet_layout(const std::vector<std::string>& row_labels,
                                        const std::vector<std::string>& col_labels,
                                        int mask_width, int mask_height, bool has_reference,
                                        const ContactSheetStyle& style = {},
                                        const std::vector<std::vector<std::string>>* captions = nullptr);

// Box filter by an integer factor: output is ceil(w/factor) × ceil(h/factor), each pixel the
// mean of its factor × factor source block; blocks cut by the right or bottom edge average only
// the pixels present (no source pixel is dropped). Every channel; factor >= 1.
ImageF box_downscale(const ImageF& image, int factor);

// The sheet in [0,1]: cells[row][column] (nullptr → mid-grey cell), with the reference (when
// given) as an extra first column labelled "REF". The images are masks (1 channel) or shaded
// images (3 channels, linear RGB), all of one size and channel count, and so is the sheet (the
// style's grey levels in every channel); otherwise, or with no image at all, throws
// InputError("contact sheet", …). cells must have one row per row label and one entry per
// column label; captions, when given, likewise: each drawn centred under its cell (e.g. the
// cell's total score).
ImageF contact_sheet(const std::vector<std::string>& row_labels,
                     const std::vector<std::string>& col_labels,
                     const std::vector<std::vector<const ImageF*>>& cells, const ImageF* reference,
                     const ContactSheetStyle& style = {},
                     const std::vector<std::vector<std::string>>* captions = nullptr);

}  // namespace shadowlab
