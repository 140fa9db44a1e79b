#include "lab/contact_sheet.h"

#include <algorithm>

#include "core/error.h"
#include "util/bitmap_font.h"

namespace shadowlab {

ContactSheetLayout contact_sheet_layout(const std::vector<std::string>& row_labels,
                                        const std::vector<std::string>& col_labels,
                                        int mask_width, int mask_height, bool has_reference,
                                        const ContactSheetStyle& style,
                                        const std::vector<std::vector<std::string>>* captions) {
  SL_CHECK(mask_width >= 1 && mask_height >= 1);
  SL_CHECK(style.max_cell_width >= 1 && style.font_scale >= 1);
  SL_CHECK(style.padding >= 0 && style.separator >= 0);
  ContactSheetLayout l;
  l.factor = (mask_width + style.max_cell_width - 1) / style.max_cell_width;
  l.cell_width = (mask_width + l.factor - 1) / l.factor;
  l.cell_height = (mask_height + l.factor - 1) / l.factor;
  // Small cells would make neighbouring column labels overlap: shrink the font for them.
  auto widest = [](const std::vector<std::string>& labels, int scale) {
    int w = 0;
    for (const std::string& s : labels) w = std::max(w, text_width(s, scale));
    return w;
  };
  std::vector<std::string> top_labels = col_labels;
  if (has_reference) top_labels.push_back("REF");
  l.font_scale = style.font_scale;
  std::vector<std::string> caption_texts;
  if (captions)
    for (const auto& row : *captions) caption_texts.insert(caption_texts.end(), row.begin(), row.end());
  while (l.font_scale > 1 && (widest(top_labels, l.font_scale) > l.cell_width + style.separator ||
                              widest(caption_texts, l.font_scale) > l.cell_width))
    l.font_scale /= 2;
  // The widest row label, then one glyph advance of background, then the grid's frame: a label
  // never reads as part of the first image.
  const int frame = std::min(style.separator, style.padding);
  l.left = style.padding + widest(row_labels, l.font_scale) + kGlyphAdvance * l.font_scale + frame;
  l.top = style.padding + text_height(l.font_scale) + style.padding;
  l.separator = style.separator;
  l.caption = captions ? text_height(l.font_scale) + 2 : 0;
  l.rows = int(row_labels.size());
  l.columns = int(col_labels.size()) + (has_reference ? 1 : 0);
  l.width = l.left + l.columns * l.cell_width + std::max(l.columns - 1, 0) * l.separator + style.padding;
  l.height = l.top + l.rows * (l.cell_height + l.caption) + std::max(l.rows - 1, 0) * l.separator +
             style.padding;
  return l;
}

ImageF box_downscale(const ImageF& image, int factor) {
  SL_CHECK(factor >= 1);
  const int w = (image.width + factor - 1) / factor, h = (image.height + factor - 1) / factor;
  ImageF out(w, h, image.channels);
  for (int c = 0; c < image.channels; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int x1 = std::min((x + 1) * factor, image.width);
        const int y1 = std::min((y + 1) * factor, image.height);
        // Double sum in a fixed (row-major) order: the same bits on every run.
        double sum = 0.0;
        for (int sy = y * factor; sy < y1; ++sy)
          for (int sx = x * factor; sx < x1; ++sx) sum += image.at(sx, sy, c);
        out.at(x, y, c) = float(sum / double((x1 - x * factor) * (y1 - y * factor)));
      }
  return out;
}

ImageF contact_sheet(const std::vector<std::string>& row_labels,
                     const std::vector<std::string>& col_labels,
                     const std::vector<std::vector<const ImageF*>>& cells, const ImageF* reference,
                     const ContactSheetStyle& style,
                     const std::vector<std::vector<std::string>>* captions) {
  SL_CHECK_EQ(cells.size(), row_labels.size());
  for (const auto& row : cells) SL_CHECK_EQ(row.size(), col_labels.size());
  if (captions) {
    SL_CHECK_EQ(captions->size(), row_labels.size());
    for (const auto& row : *captions) SL_CHECK_EQ(row.size(), col_labels.size());
  }

  // Every mask must match the first one found, since all cells share one size.
  const ImageF* first = reference;
  for (const auto& row : cells)
    for (const ImageF* m : row)
      if (!first) first = m;
  if (!first) throw InputError("contact sheet", "no masks to lay out");
  auto check = [&](const ImageF* m) {
    if (!m) return;
    if ((m->channels != 1 && m->channels != 3) || m->channels != first->channels || m->empty())
      throw InputError("contact sheet", "images must be non-empty, all 1-channel or all 3-channel");
    if (m->width != first->width || m->height != first->height)
      throw InputError("contact sheet", "masks differ in size (" + std::to_string(m->width) + "x" +
                                            std::to_string(m->height) + " vs " +
                                            std::to_string(first->width) + "x" +
                                            std::to_string(first->height) + ")");
  };
  check(reference);
  for (const auto& row : cells)
    for (const ImageF* m : row) check(m);

  const ContactSheetLayout l = contact_sheet_layout(row_labels, col_labels, first->width,
                                                    first->height, reference != nullptr, style,
                                                    captions);
  const int channels = first->channels;
  ImageF sheet(l.width, l.height, channels, style.background);

  // The grid block in separator grey, then the cells over it: what stays grey are the lines
  // between cells and a frame around the block, so lit (white) cells stand out from the white
  // margins. The frame is at most `padding` wide, so it never reaches a label.
  const int frame = l.rows > 0 ? std::min(style.separator, style.padding) : 0;
  const int grid_right = l.cell_x(l.columns - 1) + l.cell_width;
  const int grid_bottom = l.rows > 0 ? l.cell_y(l.rows - 1) + l.cell_height : l.top;
  for (int y = l.top - frame; y < grid_bottom + frame; ++y)
    for (int x = l.left - frame; x < grid_right + frame; ++x)
      for (int c = 0; c < channels; ++c) sheet.at(x, y, c) = style.separator_value;
  // With captions, the caption strips are margin (background), not grid.
  if (l.caption > 0)
    for (int r = 0; r < l.rows; ++r)
      for (int y = l.cell_y(r) + l.cell_height; y < l.cell_y(r) + l.cell_height + l.caption; ++y)
        for (int x = l.left - frame; x < grid_right + frame; ++x)
          for (int c = 0; c < channels; ++c) sheet.at(x, y, c) = style.background;
  auto put = [&](int row, int col, const ImageF* mask) {
    const int x0 = l.cell_x(col), y0 = l.cell_y(row);
    if (!mask) {
      for (int c = 0; c < channels; ++c)
        for (int y = 0; y < l.cell_height; ++y)
          for (int x = 0; x < l.cell_width; ++x) sheet.at(x0 + x, y0 + y, c) = style.null_value;
      return;
    }
    const ImageF small = box_downscale(*mask, l.factor);
    for (int c = 0; c < channels; ++c)
      for (int y = 0; y < l.cell_height; ++y)
        for (int x = 0; x < l.cell_width; ++x) sheet.at(x0 + x, y0 + y, c) = small.at(x, y, c);
  };
  const int col0 = reference ? 1 : 0;
  for (int r = 0; r < l.rows; ++r) {
    if (reference) put(r, 0, reference);  // repeated per row so each row reads against it
    for (size_t c = 0; c < col_labels.size(); ++c) put(r, col0 + int(c), cells[size_t(r)][c]);
  }

  // Labels: row labels left-aligned at the padding and centred on their row; column labels
  // centred over their cell in the top margin; captions centred under their cell. By
  // construction all lie inside the margins. A 3-channel sheet gets its text through a
  // 1-channel ink layer copied into every channel.
  ImageF ink_layer;
  if (channels != 1) ink_layer = ImageF(l.width, l.height, 1, -1.0f);
  ImageF& text_target = channels == 1 ? sheet : ink_layer;
  auto draw_text = [&](ImageF&, int x, int y, const std::string& t, int scale, float value) {
    shadowlab::draw_text(text_target, x, y, t, scale, value);
  };
  const int s = l.font_scale, th = text_height(s);
  for (int r = 0; r < l.rows; ++r)
    draw_text(sheet, style.padding, l.cell_y(r) + (l.cell_height - th) / 2, row_labels[size_t(r)],
              s, style.ink);
  auto col_label = [&](int col, const std::string& text) {
    const int x = l.cell_x(col) + (l.cell_width - text_width(text, s)) / 2;
    draw_text(sheet, std::max(x, 0), style.padding, text, s, style.ink);
  };
  if (reference) col_label(0, "REF");
  for (size_t c = 0; c < col_labels.size(); ++c) col_label(col0 + int(c), col_labels[c]);
  if (captions)
    for (int r = 0; r < l.rows; ++r)
      for (size_t c = 0; c < col_labels.size(); ++c) {
        const std::string& text = (*captions)[size_t(r)][c];
        const int x = l.cell_x(col0 + int(c)) + (l.cell_width - text_width(text, s)) / 2;
        draw_text(sheet, std::max(x, 0), l.cell_y(r) + l.cell_height + 1, text, s, style.ink);
      }
  if (channels != 1)
    for (size_t i = 0; i < ink_layer.pixel_count(); ++i)
      if (ink_layer.data[i] >= 0.0f)
        for (int c = 0; c < channels; ++c) sheet.data[size_t(c) * sheet.pixel_count() + i] = ink_layer.data[i];
  return sheet;
}

}  // namespace shadowlab
