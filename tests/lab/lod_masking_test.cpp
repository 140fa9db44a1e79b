// The LOD masking experiment on a small image: the full mesh is its own reference, simplified
// levels differ from it, and the levels carry the simplifier's counts.
#include "lab/lod_masking.h"

#include <gtest/gtest.h>

#include "scenes/scene_library.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

TEST(LodMasking, FullMeshIsItsOwnReferenceAndCoarserLevelsDiffer) {
  Scene scene = make_builtin_scene("bunny");
  apply_camera_size(scene, 160, 120);
  MaskingConfig c;
  c.levels = {300, 5000};  // the full mesh is added first
  c.slides = {"grid:amp=1,freq=0", "grid:amp=1,freq=15"};
  c.technique = "psm:res=512";
  c.repeats = 1;
  const MaskingResult r = run_lod_masking(scene, c);
  ASSERT_EQ(r.levels.size(), 3u);
  EXPECT_EQ(r.levels[0].target, 0u);
  EXPECT_EQ(r.levels[0].triangles, 69451u);  // the asset's count (design: "approx. 69,000")
  for (size_t k = 0; k < 2; ++k) {
    // Compared with itself: SSIM exactly 1, no error.
    EXPECT_DOUBLE_EQ(r.levels[0].cells[k].ssim, 1.0);
    EXPECT_EQ(r.levels[0].cells[k].rmse, 0.0);
    EXPECT_EQ(r.levels[0].cells[k].visible.plain, 0.0);
  }
  // Simplified levels: within 5 % of their targets, and visibly different from the full mesh
  // (300 triangles changes the silhouette), the coarser the worse under the plain spot.
  EXPECT_NEAR(double(r.levels[1].triangles), 300.0, 15.0);
  EXPECT_NEAR(double(r.levels[2].triangles), 5000.0, 250.0);
  for (size_t L = 1; L < 3; ++L)
    for (size_t k = 0; k < 2; ++k) {
      const MaskingCell& cell = r.levels[L].cells[k];
      EXPECT_LT(cell.ssim, 1.0);
      EXPECT_GT(cell.rmse, 0.0);
      EXPECT_GT(cell.visible.plain, 0.0);
      EXPECT_LE(cell.visible.masked, cell.visible.plain);
    }
  EXPECT_LT(r.levels[1].cells[0].ssim, r.levels[2].cells[0].ssim);
  // The text: one cost line per level, with its triangle count and where its mesh came from.
  const std::string text = masking_tables(r);
  const size_t costs = text.find("level costs");
  ASSERT_NE(costs, std::string::npos);
  EXPECT_NE(text.find("69451", costs), std::string::npos);
  EXPECT_NE(text.find("original", costs), std::string::npos);
  EXPECT_NE(text.find(std::to_string(r.levels[1].triangles), costs), std::string::npos);
  EXPECT_NE(text.find(std::to_string(r.levels[2].triangles), costs), std::string::npos);
  // The sheet: one row per level, one column per slide.
  const ImageF sheet = masking_contact_sheet(r);
  EXPECT_GT(sheet.width, 2 * 160);
  EXPECT_GT(sheet.height, 3 * 120);
}

// The default configuration is the experiment docs/programs/projector_masking.md describes:
// the full mesh and three levels, the paper's four slides, psm:res=2048,pcf=3, ambient 0.1.
TEST(LodMasking, DefaultsAreTheDocumentedExperiment) {
  const MaskingConfig c;
  EXPECT_EQ(c.levels, (std::vector<size_t>{0, 5000, 1000, 300}));
  EXPECT_EQ(c.slides, (std::vector<std::string>{"grid:amp=1,freq=0", "grid:amp=1,freq=4", "grid:amp=1,freq=15",
                                                "grid:amp=0.5,freq=15"}));
  EXPECT_EQ(c.technique, "psm:res=2048,pcf=3");
  EXPECT_EQ(c.ambient, 0.1f);
}

TEST(LodMasking, SlideLabelsAreAmplitudeAndFrequency) {
  EXPECT_EQ(masking_slide_label("grid:amp=1,freq=15"), "A1 F15");
  EXPECT_EQ(masking_slide_label("grid:amp=0.25,freq=0"), "A0.25 F0");
  EXPECT_EQ(masking_slide_label("grid:freq=7,amp=3"), "A3 F7");
  EXPECT_EQ(masking_slide_label("spot"), "spot");
}

TEST(LodMasking, BadSlideNamesTheFlag) {
  Scene scene = make_builtin_scene("bunny");
  apply_camera_size(scene, 32, 24);
  MaskingConfig c;
  c.slides = {"stripes"};
  try {
    run_lod_masking(scene, c);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--slides"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadowlab
