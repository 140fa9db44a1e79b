// The sweep's scores behave as the paper's do: they rise with shadow-map resolution.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "core/error.h"
#include "scenes/scene_library.h"
#include "lab/contact_sheet.h"
#include "lab/sweep.h"
#include "raster/gbuffer_pass.h"
#include "techniques/shading/scene_shading.h"

namespace shadowlab {
namespace {

TEST(Sweep, FidelityAndDetailRiseWithResolution) {
  Scene scene = make_builtin_scene("default");
  scene.camera.width = 256;
  scene.camera.height = 192;
  SweepConfig c;
  c.resolutions = {32, 128, 512};
  c.spp = 16;
  c.repeats = 1;
  const SweepResult r = run_resolution_sweep(scene, c);
  ASSERT_EQ(r.rows.size(), 3u);
  // The reference compared with itself is perfect in every submetric.
  const MetricReport& ref = r.reference.report;
  for (double v : {ref.c10, ref.c50, ref.c90, ref.dark, ref.lit, ref.acne, ref.noise, ref.detail})
    EXPECT_DOUBLE_EQ(v, 1.0);
  // FLIP of the reference against itself is 0, on the masks and on the shaded images; a 32²
  // map's shadows are visibly off (more FLIP than a 512² map's), on both.
  EXPECT_EQ(ref.flip_mean, 0.0);
  EXPECT_EQ(r.reference.flip_shaded, 0.0);
  EXPECT_GT(r.rows[0].report.flip_mean, r.rows[2].report.flip_mean);
  EXPECT_GT(r.rows[0].flip_shaded, r.rows[2].flip_shaded);
  EXPECT_GT(r.rows[2].flip_shaded, 0.0);
  // Finer maps: more texels per pixel (detail) and a better match (fidelity).
  EXPECT_LT(r.rows[0].report.detail, r.rows[1].report.detail);
  EXPECT_LT(r.rows[1].report.detail, r.rows[2].report.detail);
  EXPECT_LT(r.rows[0].report.fidelity, r.rows[2].report.fidelity);
  EXPECT_EQ(r.reference.technique, "rt");
  for (const SweepRow& row : r.rows) {
    EXPECT_EQ(row.technique, "csm");
    EXPECT_GT(row.result.shadow_ms(), 0.0);
    EXPECT_GE(row.result.faces_rendered, 1);
    EXPECT_LE(row.result.faces_rendered, 6);
  }
  // Plot points: one per row (not the reference), carrying the row's numbers.
  const std::vector<PlotPoint> points = sweep_plot_points(r);
  ASSERT_EQ(points.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(points[i].label, r.rows[i].label);
    EXPECT_EQ(points[i].series, "csm");
    EXPECT_EQ(points[i].time_ms, r.rows[i].result.shadow_ms());
    EXPECT_EQ(points[i].total, r.rows[i].report.total);
    EXPECT_EQ(points[i].fidelity, r.rows[i].report.fidelity);
  }
  // Contact sheet: 1 technique row, REF + 3 resolution columns of 256×192 masks (factor 1), so
  // each cell holds its mask unchanged, reference first.
  const ImageF sheet = sweep_contact_sheet(r, c);
  std::vector<std::vector<std::string>> captions(1);
  for (const SweepRow& row : r.rows) captions[0].push_back(fmt::format("total {:.3f}", row.report.total));
  const ContactSheetLayout l =
      contact_sheet_layout({"CSM"}, {"32", "128", "512"}, 256, 192, true, {}, &captions);
  ASSERT_EQ(l.factor, 1);
  ASSERT_EQ(sheet.width, l.width);
  ASSERT_EQ(sheet.height, l.height);
  for (int col = 0; col < 4; ++col) {
    const ImageF& m = col == 0 ? r.reference.result.mask : r.rows[size_t(col - 1)].result.mask;
    int differ = 0;
    for (int y = 0; y < 192; ++y)
      for (int x = 0; x < 256; ++x)
        differ += sheet.at(l.cell_x(col) + x, l.cell_y(0) + y) != m.at(x, y);
    EXPECT_EQ(differ, 0) << "column " << col;
  }
  // The shaded sheet: the same layout in RGB, each cell the row's shaded image (shade_scene of
  // its mask; factor 1 here).
  SweepConfig shaded_config = c;
  shaded_config.shaded_sheet = true;
  const ImageF colour = sweep_contact_sheet(r, shaded_config);
  ASSERT_EQ(colour.channels, 3);
  ASSERT_EQ(colour.height, l.height);
  const ImageF shaded = shade_scene(scene, render_gbuffer(scene), r.rows[2].result.mask, c.ambient);
  int differ = 0;
  for (int ch = 0; ch < 3; ++ch)
    for (int y = 0; y < 192; ++y)
      for (int x = 0; x < 256; ++x) differ += colour.at(l.cell_x(3) + x, l.cell_y(0) + y, ch) != shaded.at(x, y, ch);
  EXPECT_EQ(differ, 0);
}

// The number under each cell says what it is: the sheet is exactly the one whose captions read
// "total 0.834" (the row's total, named, 3 decimals).
// The suite table: one column per scene headed by its name cut to 11 characters (the column's
// width), one line per technique row with each scene's score, their mean and the worst.
// The progress line counts the steps of the whole sweep: the reference and every technique at
// every resolution, 1 + 2 × 2 = 5 here, from [0/5] to [5/5].
TEST(Sweep, ProgressCountsTheReferenceAndEveryRow) {
  Scene scene = make_builtin_scene("default");
  scene.camera.width = 48;
  scene.camera.height = 32;
  SweepConfig c;
  c.techniques = {"csm", "cvsm"};
  c.resolutions = {32, 64};
  c.spp = 4;
  c.repeats = 1;
  c.progress = true;
  testing::internal::CaptureStderr();
  const SweepResult r = run_resolution_sweep(scene, c);
  const std::string err = testing::internal::GetCapturedStderr();
  ASSERT_EQ(r.rows.size(), 4u);
  EXPECT_NE(err.find("[0/5] reference"), std::string::npos) << err;
  EXPECT_NE(err.find("[5/5] "), std::string::npos) << err;
  EXPECT_EQ(err.find("[6/"), std::string::npos) << err;
}

TEST(Sweep, SuiteTableHasAColumnPerSceneAndTheMeanAndWorst) {
  std::vector<SweepResult> results(2);
  results[0].scene = "depth_range_far";
  results[1].scene = "plane";
  const double fid[2][2] = {{0.5, 0.75}, {0.25, 1.0}};
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 2; ++i) {
      SweepRow row;
      row.label = i == 0 ? "CSM 64" : "CSM 128";
      row.report.fidelity = fid[k][i];
      row.report.total = fid[k][i];
      results[size_t(k)].rows.push_back(row);
    }
  const std::string t = suite_table(results);
  const std::string header = t.substr(0, t.find('\n'));
  EXPECT_NE(header.find(" depth_range       plane"), std::string::npos) << header;  // 11 wide, right-aligned
  EXPECT_EQ(header.find("depth_range_"), std::string::npos) << header;
  // CSM 64: 0.500 and 0.250, mean 0.375, worst 0.250 on plane.
  // Labels padded to 18, scores 11 wide after a space, mean and worst 8 wide.
  EXPECT_NE(t.find("CSM 64                   0.500       0.250    0.375    0.250  plane\n"), std::string::npos) << t;
  EXPECT_NE(t.find("CSM 128                  0.750       1.000    0.875    0.750  depth_range_far\n"),
            std::string::npos) << t;
}

// The label column is as wide as the longest label (at least 18), so every row's scores sit
// under their headers: "c10" and its value are right-aligned in 6 after the label column and a space.
TEST(Sweep, TableLabelColumnFitsTheLongestLabel) {
  SweepResult r;
  r.reference.label = "RT 16spp";
  SweepRow row;
  row.label = "cvsm:res=1024,blur=5,bleed=0.2";  // 30 characters
  row.report.c10 = 0.125;
  r.rows.push_back(row);
  const std::string t = sweep_table(r);
  std::vector<std::string> lines;
  for (size_t b = 0, e; (e = t.find('\n', b)) != std::string::npos; b = e + 1) lines.push_back(t.substr(b, e - b));
  ASSERT_EQ(lines.size(), 3u) << t;
  // Both end at column 30 + 1 + 6.
  EXPECT_EQ(lines[0].find("c10") + 3, 37u) << lines[0];
  EXPECT_EQ(lines[2].find("0.125") + 5, 37u) << lines[2];
  EXPECT_EQ(lines[1].substr(0, 31), "RT 16spp" + std::string(23, ' ')) << lines[1];
}

// A result read back needs its provenance's command as a list: missing, or of another type,
// it is refused naming the file.
TEST(Sweep, ResultWithoutACommandListIsRefused) {
  SweepResult r;
  r.scene = "plane";
  r.provenance = {{"program", "resolution_sweep"}, {"command", {"--quick"}}};
  const nlohmann::json good = sweep_json(r);
  EXPECT_NO_THROW(sweep_from_json(good, "s.json"));
  for (const nlohmann::json& command : {nlohmann::json("--quick"), nlohmann::json(nullptr)}) {
    nlohmann::json bad = good;
    bad["provenance"]["command"] = command;
    try {
      sweep_from_json(bad, "s.json");
      ADD_FAILURE() << command;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "s.json: its provenance has no command") << command;
    }
  }
  nlohmann::json none = good;
  none["provenance"].erase("command");
  EXPECT_THROW(sweep_from_json(none, "s.json"), InputError);
}

TEST(Sweep, ContactSheetCaptionsNameTheScore) {
  SweepConfig c;
  c.techniques = {"csm:pcf=3"};
  c.resolutions = {64};
  SweepResult r;
  r.reference.result.mask = ImageF(64, 48, 1, 1.0f);
  SweepRow row;
  row.result.mask = ImageF(64, 48, 1, 0.25f);
  row.report.total = 0.8341;
  r.rows = {row};
  const ImageF sheet = sweep_contact_sheet(r, c);
  const std::vector<std::vector<std::string>> captions = {{"total 0.834"}};
  const ImageF expected = contact_sheet({"CSM:PCF=3"}, {"64"}, {{&r.rows[0].result.mask}},
                                        &r.reference.result.mask, {}, &captions);
  ASSERT_EQ(sheet.width, expected.width);
  ASSERT_EQ(sheet.height, expected.height);
  EXPECT_TRUE(sheet.data == expected.data);
}

}  // namespace
}  // namespace shadowlab
