#pragma once
// The slide-projector masking experiment (Dowling, Figures 6–11): the bunny at several levels
// of detail under several slides; each level's shaded image is compared with the full mesh's
// image under the same slide (SSIM, RMSE, visible-difference shares), with the time the level
// costs.
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "metric/visible_difference.h"

namespace shadowlab {

struct MaskingConfig {
  std::vector<size_t> levels = {0, 5000, 1000, 300};  // target triangles; 0 = the full mesh
  std::vector<std::string> slides = {"grid:amp=1,freq=0", "grid:amp=1,freq=4",
                                     "grid:amp=1,freq=15", "grid:amp=0.5,freq=15"};
  std::string technique = "psm:res=2048,pcf=3";  // visibility of the shaded images
  float ambient = 0.1f;
  int repeats = 3;              // timing repeats (median)
  std::string cache_dir;        // LOD cache folder; empty = none
  std::string out_dir;          // shaded PNGs per cell when non-empty
};

struct MaskingCell {
  double ssim = 1.0;            // of the display-encoded luminance images
  double rmse = 0.0;            // same images, [0, 1] display units
  VisibleDifference visible;
  ImageF shaded_luma;           // linear luminance (for the contact sheet)
};

struct MaskingLevel {
  size_t target = 0;            // requested triangles (0 = full)
  size_t triangles = 0;         // the bunny mesh's actual count
  bool from_cache = false;
  double camera_ms = 0.0;       // camera pass, median
  double shadow_ms = 0.0;       // the technique's map + lookup, median over the slides' runs
  std::vector<MaskingCell> cells;  // one per slide
};

struct MaskingResult {
  int width = 0, height = 0;
  std::vector<std::string> slides;
  std::vector<MaskingLevel> levels;
};

// `scene` must be the "bunny" built-in scene (scenes/bunny_scene.h) with its posed projector;
// throws InputError for a bad slide or technique spec (flags "--slides", "--technique").
MaskingResult run_lod_masking(const Scene& scene, const MaskingConfig& config);

// Tables: one per measure (SSIM, RMSE, visible %, masked visible %), rows = levels, columns =
// slides, plus a level table with triangles and times.
std::string masking_tables(const MaskingResult& result);
void write_masking_csv(const std::string& path, const MaskingResult& result);
// Contact sheet in the layout of the paper's Figures 6–9: one row per level, one column per
// slide, shaded luminance, cells box-downscaled to at most max_cell_width px.
// A slide's column label on the sheet: "grid:amp=1,freq=15" → "A1 F15" (any order of the two
// keys); a slide without both keys keeps its name.
std::string masking_slide_label(const std::string& slide);
ImageF masking_contact_sheet(const MaskingResult& result, int max_cell_width = 256);

}  // namespace shadowlab
