// Temporal stability (lab/flicker_run.h): the sums against a brute-force loop, the
// paths' geometry, and the expected ordering of flicker on the default scene.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/slide.h"
#include "util/bitmap_font.h"
#include "lab/contact_sheet.h"
#include "lab/flicker_run.h"
#include "raster/gbuffer_pass.h"
#include "scenes/scene_library.h"
#include "techniques/registry/technique.h"

namespace shadowlab {
namespace {

Scene small_default(int w = 192, int h = 144) {
  Scene s = make_builtin_scene("default");
  s.camera.width = w;
  s.camera.height = h;
  return s;
}

const FlickerRow& row_of(const FlickerResult& r, const std::string& spec, bool snapped = false) {
  for (const FlickerRow& row : r.rows)
    if (row.spec == spec && row.snapped == snapped) return row;
  ADD_FAILURE() << "no row " << spec;
  return r.rows.front();
}

TEST(Flicker, StaticPathGivesZero) {
  FlickerConfig c;
  c.techniques = {"csm", "cvsm", "cpcss"};
  c.resolutions = {128};
  c.frames = 3;
  c.step = 0.0;
  c.spp = 8;
  for (FlickerPath p : {FlickerPath::LightLine, FlickerPath::LightCircle, FlickerPath::LightJitter,
                        FlickerPath::CameraPan}) {
    c.path = p;
    const FlickerResult r = measure_flicker(small_default(96, 72), c);
    ASSERT_EQ(r.rows.size(), 3u);
    for (const FlickerRow& row : r.rows) {
      EXPECT_EQ(row.change, 0.0) << row.spec;
      EXPECT_EQ(row.ref_change, 0.0) << row.spec;
      EXPECT_EQ(row.excess, 0.0) << row.spec;
      EXPECT_EQ(row.flip_share, 0.0) << row.spec;
    }
  }
}

// The reference run as a row has no excess and no flips of its own, while it does change.
TEST(Flicker, TheReferenceHasNoExcess) {
  FlickerConfig c;
  c.techniques = {"rt", "csm"};
  c.resolutions = {128};
  c.frames = 4;
  c.spp = 16;
  c.step = 0.01;
  const FlickerResult r = measure_flicker(small_default(), c);
  const FlickerRow& rt = row_of(r, "rt:spp=16");
  EXPECT_GT(rt.ref_change, 1e-4);
  EXPECT_EQ(rt.change, rt.ref_change);
  EXPECT_EQ(rt.excess, 0.0);
  EXPECT_EQ(rt.flip_share, 0.0);
  EXPECT_GT(row_of(r, "csm:res=128").excess, 0.0);
}

// The mean change, the reference's and the flip share from a straight loop over frames and
// pixels (masks from run_technique at each frame's scene), in long double.
TEST(Flicker, SumsAreTheBruteForceMeansOfFrameDifferences) {
  // The grazing scene's floor ends inside the view: a pan of 5 cm per frame moves the covered
  // set.
  Scene scene = make_builtin_scene("grazing");
  scene.camera.width = 192;
  scene.camera.height = 144;
  FlickerConfig c;
  c.techniques = {"csm"};
  c.resolutions = {128};
  c.frames = 4;
  c.spp = 16;
  c.step = 0.05;
  c.path = FlickerPath::CameraPan;  // the GBuffer changes too: pixels covered in both frames
  const FlickerRow row = measure_flicker(scene, c).rows.at(0);
  long double change = 0, ref = 0, flips = 0, n = 0, worst = -1, moved = 0;
  int worst_t = 0;
  ImageF m_prev, r_prev;
  GBuffer g_prev;
  RunOptions opt;
  for (int f = 0; f < c.frames; ++f) {
    const Scene fs = flicker_frame_scene(scene, c, c.step, f);
    const GBuffer g = render_gbuffer(fs);
    const ImageF m = run_technique(parse_technique_spec("csm:res=128", "t"), fs, g, opt).mask;
    const ImageF r = run_technique(parse_technique_spec("rt:spp=16", "t"), fs, g, opt).mask;
    if (f > 0) {
      long double fc = 0, fr = 0, fn = 0;
      for (size_t i = 0; i < m.pixel_count(); ++i) {
        moved += g.covered[i] != g_prev.covered[i] ? 1 : 0;
        if (!g.covered[i] || !g_prev.covered[i]) continue;
        fn += 1;
        fc += std::fabs((long double)m.data[i] - m_prev.data[i]);
        fr += std::fabs((long double)r.data[i] - r_prev.data[i]);
        const bool a = (m.data[i] >= 0.5f) != (m_prev.data[i] >= 0.5f);
        const bool b = (r.data[i] >= 0.5f) != (r_prev.data[i] >= 0.5f);
        flips += a && !b ? 1 : 0;
      }
      change += fc;
      ref += fr;
      n += fn;
      if ((fc - fr) / fn > worst) {
        worst = (fc - fr) / fn;
        worst_t = f;
      }
    }
    m_prev = m;
    r_prev = r;
    g_prev = g;
  }
  ASSERT_GT(n, 0);
  EXPECT_GT(moved, 0) << "the covered set should change between frames";
  EXPECT_GT(double(change / n), 1e-4);
  EXPECT_NEAR(row.change, double(change / n), 1e-12);
  EXPECT_NEAR(row.ref_change, double(ref / n), 1e-12);
  EXPECT_NEAR(row.excess, double((change - ref) / n), 1e-12);
  EXPECT_NEAR(row.flip_share, double(flips / n), 1e-12);
  EXPECT_EQ(row.worst_frame, worst_t);
  EXPECT_NEAR(row.worst_excess, double(worst), 1e-12);
}

// The line runs along world x when the light–target direction is vertical (the plane scene:
// light straight above the target), f·step per frame; a projector moves with its light.
TEST(Flicker, LineAlongXForAVerticalLightAndTheProjectorFollows) {
  Scene s = make_builtin_scene("plane");
  FlickerConfig c;
  c.frames = 8;
  c.path = FlickerPath::LightLine;
  const vec3 d = flicker_frame_scene(s, c, 0.01, 5).light.position - s.light.position;
  EXPECT_NEAR(d.x, 0.05, 1e-6);
  EXPECT_NEAR(d.y, 0.0, 1e-7);
  EXPECT_NEAR(d.z, 0.0, 1e-7);
  Projector p;
  p.position = vec3(0.5f, 3.0f, 0.2f);
  p.direction = vec3(0.0f, -1.0f, 0.1f);
  p.slide = make_slide("spot", "test");
  set_projector(s, p, "test");
  for (const FlickerPath path : {FlickerPath::LightLine, FlickerPath::LightJitter}) {
    c.path = path;
    const Scene f = flicker_frame_scene(s, c, 0.01, 3);
    ASSERT_TRUE(f.projector.enabled);
    const vec3 moved = f.light.position - s.light.position;
    EXPECT_GT(glm::length(moved), 0.001f);
    EXPECT_EQ(f.projector.position, s.projector.position + moved);
  }
}

TEST(Flicker, PathsMoveAsDocumented) {
  const Scene s = make_builtin_scene("default");
  FlickerConfig c;
  c.frames = 16;
  const double step = 0.01;
  // Line: f·step along a horizontal direction perpendicular to the light–target direction.
  c.path = FlickerPath::LightLine;
  const vec3 d = flicker_frame_scene(s, c, step, 5).light.position - s.light.position;
  EXPECT_NEAR(glm::length(d), 5 * step, 1e-6);
  EXPECT_NEAR(d.y, 0.0, 1e-7);
  EXPECT_NEAR(glm::dot(glm::normalize(d), glm::normalize(s.camera.target - s.light.position)), 0.0, 1e-6);
  // Circle: constant distance from its centre, consecutive frames `step` apart along the arc
  // (chord ≈ arc for these small angles), closed after the N frames.
  c.path = FlickerPath::LightCircle;
  const vec3 p0 = flicker_frame_scene(s, c, step, 0).light.position;
  EXPECT_NEAR(glm::length(p0 - s.light.position), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(flicker_frame_scene(s, c, step, 16).light.position - p0), 0.0, 1e-5);
  const double radius = 16 * step / (2 * M_PI);
  const double chord = 2 * radius * std::sin(step / (2 * radius));
  EXPECT_NEAR(glm::length(flicker_frame_scene(s, c, step, 3).light.position -
                          flicker_frame_scene(s, c, step, 2).light.position), chord, 1e-6);
  // It sets out along u × up, u the line path's direction (its centre lies along −u): the first
  // chord, over 2π/16 of the circle, is π/16 from that tangent.
  const vec3 first = flicker_frame_scene(s, c, step, 1).light.position - p0;
  EXPECT_NEAR(glm::dot(glm::normalize(first), glm::normalize(glm::cross(glm::normalize(d), vec3(0.0f, 1.0f, 0.0f)))),
              std::cos(M_PI / 16), 1e-5);
  // Pan: eye and target by the same f·step along the camera's right vector; the light stays.
  c.path = FlickerPath::CameraPan;
  const Scene pan = flicker_frame_scene(s, c, step, 4);
  EXPECT_NEAR(glm::length(pan.camera.eye - s.camera.eye), 4 * step, 1e-6);
  EXPECT_NEAR(glm::length((pan.camera.eye - s.camera.eye) - (pan.camera.target - s.camera.target)), 0.0, 1e-6);
  EXPECT_EQ(pan.light.position, s.light.position);
  // Jitter: within ±step of the base per axis, a different offset each frame.
  c.path = FlickerPath::LightJitter;
  const vec3 j1 = flicker_frame_scene(s, c, step, 1).light.position - s.light.position;
  const vec3 j2 = flicker_frame_scene(s, c, step, 2).light.position - s.light.position;
  for (int a = 0; a < 3; ++a) EXPECT_LE(std::fabs(j1[a]), step * (1 + 1e-5));
  EXPECT_GT(glm::length(j1 - j2), 0.1 * step);
  // Uniform on [−step, step) per axis: over 256 frames every offset is inside, each axis has
  // both signs, and its mean is 0 within 0.2·step (the mean's deviation is
  // step / √(3 · 256) = 0.036·step).
  vec3 sum(0.0f);
  int negative[3] = {0, 0, 0};
  for (int f = 0; f < 256; ++f) {
    const vec3 j = flicker_frame_scene(s, c, step, f).light.position - s.light.position;
    for (int a = 0; a < 3; ++a) {
      ASSERT_LE(std::fabs(j[a]), step * (1 + 1e-5)) << "frame " << f;
      negative[a] += j[a] < 0.0f;
    }
    sum += j;
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(sum[a] / 256.0, 0.0, 0.2 * step) << "axis " << a;
    EXPECT_GT(negative[a], 64) << "axis " << a;
    EXPECT_LT(negative[a], 192) << "axis " << a;
  }
  // Snapping: every coordinate the base's plus a multiple of the grid, within half a cell of
  // the true one.
  c.path = FlickerPath::LightLine;
  const double g = flicker_snap(s, 128);
  EXPECT_NEAR(g, 2.0 * glm::length(s.camera.target - s.light.position) / 128.0, 1e-9);
  const Scene snapped = flicker_frame_scene(s, c, step, 3, g);
  const vec3 truth = flicker_frame_scene(s, c, step, 3).light.position;
  for (int a = 0; a < 3; ++a) {
    const double k = double(snapped.light.position[a] - s.light.position[a]) / g;
    EXPECT_NEAR(k, std::round(k), 1e-3);
    EXPECT_LE(std::fabs(double(snapped.light.position[a] - truth[a])), 0.5 * g + 1e-6);
  }
}

// The expected ordering on the default scene, the light moving by a quarter of a 1024-map
// texel per frame: a 128² map flickers more than a 1024² one, and VSM less than one-tap depth
// compare at equal resolution. Measured (this configuration): excess csm 0.00088
// (128) and 0.00047 (1024), a ratio of 1.87; cvsm 0.00078 and 0.00039.
TEST(Flicker, CoarseMapsFlickerMoreAndVsmLess) {
  const Scene scene = small_default(256, 192);
  FlickerConfig c;
  c.techniques = {"csm", "cvsm"};
  c.resolutions = {128, 1024};
  c.frames = 12;
  c.spp = 16;
  const FlickerResult r = measure_flicker(scene, c);
  const FlickerRow& csm128 = row_of(r, "csm:res=128");
  const FlickerRow& csm1024 = row_of(r, "csm:res=1024");
  EXPECT_GT(csm128.excess, 1.5 * csm1024.excess);
  EXPECT_LT(row_of(r, "cvsm:res=128").excess, csm128.excess);
  EXPECT_LT(row_of(r, "cvsm:res=1024").excess, csm1024.excess);
}

// A light wobbling in place by up to a quarter of a 1024-map texel: every map flickers, and
// with texel snapping (a grid of at least 4 steps) every frame's map is the base light's, so
// the snapped rows do not change at all: their excess is minus the reference's change.
// Measured plain changes: 0.00038–0.00070.
TEST(Flicker, SnappingRemovesTheShimmerOfAWobblingLight) {
  FlickerConfig c;
  c.techniques = {"csm", "cvsm"};
  c.resolutions = {128, 1024};
  c.path = FlickerPath::LightJitter;
  c.frames = 6;
  c.spp = 16;
  c.jitter = true;
  const FlickerResult r = measure_flicker(small_default(), c);
  for (const char* spec : {"csm:res=128", "csm:res=1024", "cvsm:res=128", "cvsm:res=1024"}) {
    const FlickerRow& plain = row_of(r, spec);
    const FlickerRow& snapped = row_of(r, spec, true);
    EXPECT_GT(plain.change, 1e-4) << spec;
    EXPECT_EQ(snapped.change, 0.0) << spec;
    EXPECT_EQ(snapped.flip_share, 0.0) << spec;
    EXPECT_EQ(snapped.excess, -snapped.ref_change) << spec;
  }
  EXPECT_GT(row_of(r, "csm:res=128").flip_share, 0.0);
}

TEST(Flicker, SameNumbersAtAnyThreadCount) {
  FlickerConfig c;
  c.techniques = {"csm", "cmsm", "tpcss"};
  c.resolutions = {256};
  c.frames = 3;
  c.spp = 8;
  std::vector<FlickerResult> runs;
  const int before = thread_count();
  for (int t : {1, 2, 7}) {
    set_thread_count(t);
    runs.push_back(measure_flicker(small_default(128, 96), c));
  }
  set_thread_count(before);
  for (size_t i = 1; i < runs.size(); ++i)
    for (size_t k = 0; k < runs[0].rows.size(); ++k) {
      EXPECT_EQ(runs[i].rows[k].change, runs[0].rows[k].change);
      EXPECT_EQ(runs[i].rows[k].excess, runs[0].rows[k].excess);
      EXPECT_EQ(runs[i].rows[k].flip_share, runs[0].rows[k].flip_share);
    }
}

TEST(Flicker, DefaultStepsAreAQuarterTexelOrAQuarterPixel) {
  // Light paths: a quarter of the finest map's texel, 2·|L − target|/res; camera-pan: a quarter
  // of a pixel at the target, 2·|target − eye|·tan(fov/2)/height (long double here).
  const Scene s = make_builtin_scene("default");
  FlickerConfig c;
  c.resolutions = {256, 1024};
  c.path = FlickerPath::LightLine;
  const long double lt = glm::length(s.light.position - s.camera.target);
  EXPECT_NEAR(flicker_default_step(s, c), double(0.25L * 2.0L * lt / 1024.0L), 1e-7);
  c.path = FlickerPath::CameraPan;
  const long double d = glm::length(s.camera.target - s.camera.eye);
  const long double pixel =
      2.0L * d * std::tan(s.camera.fov_y_deg * 3.14159265358979323846L / 360.0L) / s.camera.height;
  EXPECT_NEAR(flicker_default_step(s, c), double(0.25L * pixel), 1e-7);
}

TEST(Flicker, BadConfigIsRejectedBeforeAnyWork) {
  const Scene s = small_default(64, 48);
  auto fails = [&](FlickerConfig c, const std::string& flag) {
    try {
      validate_flicker(s, c);
      ADD_FAILURE() << "accepted a bad config for " << flag;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
    }
  };
  FlickerConfig ok;
  ok.techniques = {"csm"};
  EXPECT_NO_THROW(validate_flicker(s, ok));
  FlickerConfig c = ok;
  c.frames = 1;
  fails(c, "--frames");
  c = ok;
  c.path = FlickerPath::CameraPan;
  c.jitter = true;
  fails(c, "--jitter");
  c = ok;
  c.techniques = {"csm:res=512"};
  fails(c, "--techniques");
  c = ok;
  c.techniques = {"csm:pcf=0"};
  fails(c, "--techniques");
  c = ok;
  c.techniques = {"psm"};  // needs a slide projector
  fails(c, "--techniques");
  c = ok;
  c.techniques = {"rt:spp=4"};
  fails(c, "--techniques");
  EXPECT_THROW(parse_flicker_path("light-zigzag", "--path"), InputError);
}

// flicker_worst.png says which strip is which: its top row is labelled "TECHNIQUE" and the spec,
// the bottom one "REFERENCE", each column with its frame. The ink left of each row band is
// exactly its label's glyphs (counted from draw_text of the label alone).
TEST(Flicker, WorstStripLabelsTechniqueAndReference) {
  const Scene scene = small_default(96, 72);
  FlickerConfig c;
  c.techniques = {"csm"};
  c.resolutions = {64};
  c.frames = 4;
  c.spp = 4;
  c.step = 0.01;
  FlickerRow row;
  row.spec = "csm:res=64";
  row.technique = "csm";
  row.res = 64;
  row.worst_frame = 2;
  const ImageF strip = flicker_strip(scene, c, 0.01, row, 2, 1);
  // Frames 1 and 2 (the two around frame 2 that start at 1 or later).
  const std::vector<std::string> labels = {"TECHNIQUE CSM:RES=64", "REFERENCE"};
  ContactSheetStyle style;
  style.max_cell_width = 96;
  const ContactSheetLayout l = contact_sheet_layout(labels, {"FRAME 1", "FRAME 2"}, 96, 72, false, style);
  ASSERT_EQ(strip.width, l.width);
  ASSERT_EQ(strip.height, l.height);
  for (int r = 0; r < 2; ++r) {
    int ink = 0;
    for (int y = l.cell_y(r); y < l.cell_y(r) + l.cell_height; ++y)
      for (int x = 0; x < l.left - l.separator; ++x) ink += strip.at(x, y) == style.ink;
    ImageF alone(text_width(labels[size_t(r)], l.font_scale), text_height(l.font_scale), 1, 1.0f);
    draw_text(alone, 0, 0, labels[size_t(r)], l.font_scale, 0.0f);
    int expected = 0;
    for (float v : alone.data) expected += v == 0.0f;
    EXPECT_EQ(ink, expected) << labels[size_t(r)];
  }
}

}  // namespace
}  // namespace shadowlab
