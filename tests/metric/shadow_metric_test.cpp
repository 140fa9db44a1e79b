#include "metric/shadow_metric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metric/box_blur.h"
#include "metric/contour.h"
#include "metric/image_error.h"
#include "metric/metric_report.h"

namespace shadowlab {
namespace {

// A soft-edged disc shadow with speckles: exercises every submetric.
ImageF soft_shadow(int w, int h, double cx, double cy, double radius, uint32_t seed) {
  ImageF m(w, h, 1);
  std::mt19937 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
      double v = std::clamp((d - radius) / 6.0 + 0.5, 0.0, 1.0);
      if (rng() % 50 == 0) v = 1.0 - v;
      m.at(x, y) = float(v);
    }
  return m;
}

ImageF half_dark(int w, int h) {
  ImageF m(w, h, 1, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x) m.at(x, y) = 0.0f;
  return m;
}

void expect_all_scores_one(const MetricReport& r) {
  for (const double v : {r.c10, r.c50, r.c90, r.dark, r.lit, r.acne, r.noise, r.detail,
                         r.performance, r.fidelity, r.aesthetics, r.total})
    EXPECT_EQ(v, 1.0);
  EXPECT_NEAR(r.ssim, 1.0, 1e-12);
  EXPECT_EQ(r.rmse, 0.0);
  EXPECT_EQ(r.psnr, kPsnrCapDb);
}

TEST(ShadowMetric, IdenticalMasksScoreOneEverywhere) {
  const ImageF m = soft_shadow(160, 120, 70, 60, 30, 1);
  ImageU32 texels(160, 120, 1);
  for (size_t i = 0; i < texels.data.size(); ++i) texels.data[i] = uint32_t(i);  // 1 px/texel
  const Timings free_shadows{5.0, 5.0};
  expect_all_scores_one(compute_metric(m, m, &texels, &free_shadows));
}

TEST(ShadowMetric, AllLitAgainstAllLit) {
  const ImageF lit(64, 48, 1, 1.0f);
  const MetricReport r = compute_metric(lit, lit, nullptr, nullptr);
  expect_all_scores_one(r);
  EXPECT_FALSE(r.has_performance);
}

TEST(ShadowMetric, SinglePixelImages) {
  // 1×1, test dark, reference lit. A lone pixel is a contour only if it equals the level, so
  // neither has a contour → c = 1. Dark region empty → 1; the lit region (1 pixel) is missed →
  // 0. No Roberts cells → acne = noise = 1. SSIM of constants 0 and 1: C1/(1 + C1). RMSE 1.
  const ImageF dark(1, 1, 1, 0.0f), lit(1, 1, 1, 1.0f);
  const MetricReport r = compute_metric(dark, lit, nullptr, nullptr);
  EXPECT_EQ(r.c10, 1.0);
  EXPECT_EQ(r.c50, 1.0);
  EXPECT_EQ(r.c90, 1.0);
  EXPECT_EQ(r.dark, 1.0);
  EXPECT_EQ(r.lit, 0.0);
  EXPECT_EQ(r.acne, 1.0);
  EXPECT_EQ(r.noise, 1.0);
  EXPECT_NEAR(r.ssim, 1e-4 / (1.0 + 1e-4), 1e-15);
  EXPECT_EQ(r.rmse, 1.0);
  EXPECT_EQ(r.psnr, 0.0);
  EXPECT_FALSE(std::signbit(r.psnr));  // +0, so it prints as 0.000000
  // Thin images run through every stage too.
  for (const auto& s : {std::pair{1, 9}, std::pair{9, 1}, std::pair{2, 2}}) {
    const ImageF m = soft_shadow(s.first, s.second, 0.5, 0.5, 2.0, 5);
    expect_all_scores_one(compute_metric(m, m, nullptr, nullptr));
  }
}

TEST(ShadowMetric, GroupsAndTotalOnHandAnalyzedCase) {
  // 64×48 (k = 1). Reference: left half dark; test: all lit.
  // Contours: only the reference has one → c10 = c50 = c90 = 0. Dark coverage 0, lit 1.
  // Acne: the lit cells are flat in both → 1. Noise: the test is flat (T_RMS = 0) → 1.
  // Detail: no texels → 1. Fidelity = 1/5, aesthetics = 1.
  const ImageF ref = half_dark(64, 48);
  const ImageF test(64, 48, 1, 1.0f);
  const MetricReport r = compute_metric(test, ref, nullptr, nullptr);
  EXPECT_EQ(r.blur_size, 1);
  EXPECT_EQ(r.c10, 0.0);
  EXPECT_EQ(r.c50, 0.0);
  EXPECT_EQ(r.c90, 0.0);
  EXPECT_EQ(r.dark, 0.0);
  EXPECT_EQ(r.lit, 1.0);
  EXPECT_EQ(r.acne, 1.0);
  EXPECT_EQ(r.noise, 1.0);
  EXPECT_EQ(r.detail, 1.0);
  EXPECT_DOUBLE_EQ(r.fidelity, 0.2);
  EXPECT_DOUBLE_EQ(r.aesthetics, 1.0);
  EXPECT_DOUBLE_EQ(r.total, (0.2 + 1.0 + 1.0) / 3.0);  // no timings: three groups
  // Half the pixels differ by 1: RMSE √0.5, PSNR 10·log10(2).
  EXPECT_DOUBLE_EQ(r.rmse, std::sqrt(0.5));
  EXPECT_NEAR(r.psnr, 10.0 * std::log10(2.0), 1e-12);

  // One frame at 30 fps of shadow work: performance 0.5, now four groups.
  const Timings t{12.0 + 1000.0 / 30.0, 12.0};
  const MetricReport rt = compute_metric(test, ref, nullptr, &t);
  EXPECT_TRUE(rt.has_performance);
  EXPECT_NEAR(rt.performance, 0.5, 1e-12);
  EXPECT_NEAR(rt.total, (0.2 + 1.0 + 1.0 + 0.5) / 4.0, 1e-12);

  // Weights 2, 0, 1, 1: (2·0.2 + 0 + 1 + 0.5)/4.
  MetricWeights w;
  w.fidelity = 2.0;
  w.aesthetics = 0.0;
  const MetricReport rw = compute_metric(test, ref, nullptr, &t, w);
  EXPECT_NEAR(rw.total, (0.4 + 1.0 + 0.5) / 4.0, 1e-12);
}

TEST(ShadowMetric, EachContourScoreIsItsOwnLevel) {
  // Reference: a ramp x/63 across 64×48 (k = 1: no blur). Test: the ramp pivoted about the
  // 10 % level with 1.2 times the slope, so its 10 % contour is the reference's (c10 = 1) and
  // its 50 % and 90 % contours lie 63·(0.4 − 0.4/1.2) = 4.2 and 63·(0.8 − 0.8/1.2) = 8.4 pixels
  // off, against D_MAX = 0.2·√(64·48) = 11.09: c50 ≈ 0.62, c90 ≈ 0.24 (±1 pixel of contour
  // placement), each the contour score of its own level.
  ImageF ref(64, 48, 1), test(64, 48, 1);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const double v = x / 63.0;
      ref.at(x, y) = float(v);
      test.at(x, y) = float(std::clamp(0.1 + 1.2 * (v - 0.1), 0.0, 1.0));
    }
  const MetricReport r = compute_metric(test, ref, nullptr, nullptr);
  ASSERT_EQ(r.blur_size, 1);
  const ImageD bt = box_blur(test, 1), br = box_blur(ref, 1);
  EXPECT_EQ(r.c10, 1.0);
  EXPECT_EQ(r.c50, contour_score(bt, br, 0.5));
  EXPECT_EQ(r.c90, contour_score(bt, br, 0.9));
  const double dmax = 0.2 * std::sqrt(64.0 * 48.0);
  EXPECT_NEAR(r.c50, 1.0 - 4.2 / dmax, 1.0 / dmax);
  EXPECT_NEAR(r.c90, 1.0 - 8.4 / dmax, 1.0 / dmax);
}

TEST(ShadowMetric, JsonHasExactlyTheDocumentedKeys) {
  const ImageF ref = half_dark(32, 24);
  const ImageF test = soft_shadow(32, 24, 10, 12, 8, 3);
  const MetricReport r = compute_metric(test, ref, nullptr, nullptr);
  const auto j = nlohmann::json::parse(metric_report_json(r));
  std::set<std::string> keys;
  for (const auto& item : j.items()) keys.insert(item.key());
  EXPECT_EQ(keys,
            (std::set<std::string>{"c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail",
                                   "fidelity", "aesthetics", "total", "ssim", "rmse", "psnr",
                                   "flip_mean"}));
  EXPECT_NEAR(j["total"].get<double>(), r.total, 5e-7);
  EXPECT_NEAR(j["rmse"].get<double>(), r.rmse, 5e-7);

  const Timings t{20.0, 10.0};
  const auto jt = nlohmann::json::parse(metric_report_json(compute_metric(test, ref, nullptr, &t)));
  ASSERT_TRUE(jt.contains("performance"));
  EXPECT_NEAR(jt["performance"].get<double>(), 1.0 / (1.0 + 10.0 / (1000.0 / 30.0)), 5e-7);
}

TEST(ShadowMetric, JsonKeepsTheKeyOrderAndFullPrecision) {
  const ImageF lit(16, 16, 1, 1.0f);
  EXPECT_EQ(metric_report_json(compute_metric(lit, lit, nullptr, nullptr)),
            "{\"c10\":1.0,\"c50\":1.0,\"c90\":1.0,\"dark\":1.0,\"lit\":1.0,\"acne\":1.0,"
            "\"noise\":1.0,\"detail\":1.0,\"fidelity\":1.0,\"aesthetics\":1.0,\"total\":1.0,"
            "\"ssim\":1.0,\"rmse\":0.0,\"psnr\":100.0,\"flip_mean\":0.0}");
  // Values are written exactly (the old writer rounded to 6 decimals).
  const ImageF ref = half_dark(32, 24);
  const MetricReport r = compute_metric(soft_shadow(32, 24, 10, 12, 8, 3), ref, nullptr, nullptr);
  EXPECT_EQ(nlohmann::json::parse(metric_report_json(r))["total"].get<double>(), r.total);
}

TEST(ShadowMetric, TableListsEverySubmetric) {
  const ImageF lit(16, 16, 1, 1.0f);
  const std::string table = metric_report_table(compute_metric(lit, lit, nullptr, nullptr));
  for (const char* name :
       {"c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail", "performance", "fidelity",
        "aesthetics", "total", "ssim", "rmse", "psnr"})
    EXPECT_NE(table.find(name), std::string::npos) << name;
  EXPECT_NE(table.find("n/a"), std::string::npos);  // no timings
  // Each value to six decimals on its own line, −0 written as 0.
  MetricReport r;
  r.c10 = 0.1234567;
  r.c50 = -0.0;
  r.acne = 0.9999994;
  r.has_performance = true;
  r.performance = 0.5;
  r.lit = std::numeric_limits<double>::infinity();
  const std::string t = metric_report_table(r);
  auto line_of = [&](const std::string& name) {
    const size_t at = t.find(name + " ");
    return at == std::string::npos ? std::string() : t.substr(at, t.find('\n', at) - at);
  };
  EXPECT_NE(line_of("c10").find("0.123457"), std::string::npos) << t;
  EXPECT_NE(line_of("c50").find("0.000000"), std::string::npos) << t;
  EXPECT_EQ(line_of("c50").find("-0"), std::string::npos) << t;
  EXPECT_NE(line_of("acne").find("0.999999"), std::string::npos) << t;
  EXPECT_NE(line_of("performance").find("0.500000"), std::string::npos) << t;
  EXPECT_NE(line_of("lit").find("null"), std::string::npos) << t;  // not finite: null, as in JSON
}

TEST(ShadowMetric, BadInputThrowsInputError) {
  const ImageF ok(8, 8, 1, 0.5f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto with = [&](int x, int y, float v) {
    ImageF m = ok;
    m.at(x, y) = v;
    return m;
  };
  EXPECT_THROW(compute_metric(ok, ImageF(8, 9, 1, 0.5f), nullptr, nullptr), InputError);
  // Sizes that differ in one side only are refused as such, before any pass reads them.
  for (const auto& [w, h] : {std::pair{8, 9}, std::pair{9, 8}}) {
    try {
      compute_metric(ok, ImageF(w, h, 1, 0.5f), nullptr, nullptr);
      ADD_FAILURE() << w << "x" << h << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "metric: test mask is 8x8x1 but reference mask is " +
                                           std::to_string(w) + "x" + std::to_string(h) + "x1");
    }
  }
  EXPECT_THROW(compute_metric(ImageF(8, 8, 2, 0.5f), ok, nullptr, nullptr), InputError);
  EXPECT_THROW(compute_metric(ImageF(), ImageF(), nullptr, nullptr), InputError);
  EXPECT_THROW(compute_metric(with(3, 4, nan), ok, nullptr, nullptr), InputError);
  EXPECT_THROW(compute_metric(ok, with(7, 7, nan), nullptr, nullptr), InputError);
  EXPECT_THROW(
      compute_metric(ok, with(0, 0, std::numeric_limits<float>::infinity()), nullptr, nullptr),
      InputError);
  EXPECT_THROW(compute_metric(with(1, 1, 1.5f), ok, nullptr, nullptr), InputError);
  EXPECT_THROW(compute_metric(with(1, 1, -0.1f), ok, nullptr, nullptr), InputError);
  const ImageU32 texels(8, 7, 1, 0);
  EXPECT_THROW(compute_metric(ok, ok, &texels, nullptr), InputError);
  const Timings negative{-1.0, 0.0};
  EXPECT_THROW(compute_metric(ok, ok, nullptr, &negative), InputError);
  MetricWeights w;
  w.detail = -1.0;
  EXPECT_THROW(compute_metric(ok, ok, nullptr, nullptr, w), InputError);
  MetricWeights zero{0.0, 0.0, 0.0, 1.0};  // only performance weighted, but no timings
  EXPECT_THROW(compute_metric(ok, ok, nullptr, nullptr, zero), InputError);

  // The message names the image and the pixel.
  try {
    compute_metric(with(3, 4, nan), ok, nullptr, nullptr);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "metric");
    EXPECT_NE(e.reason.find("test mask"), std::string::npos) << e.reason;
    EXPECT_NE(e.reason.find("(3, 4)"), std::string::npos) << e.reason;
  }
}

// Every field, for bitwise comparison.
std::vector<double> fields(const MetricReport& r) {
  return {r.c10,
          r.c50,
          r.c90,
          r.dark,
          r.lit,
          r.acne,
          r.noise,
          r.detail,
          r.performance,
          r.fidelity,
          r.aesthetics,
          r.total,
          r.ssim,
          r.rmse,
          r.psnr,
          double(r.blur_size),
          double(r.has_performance)};
}

TEST(ShadowMetric, ReusedScratchGivesIdenticalReports) {
  // A scratch reused across calls of different sizes changes nothing.
  const ImageF big_ref = soft_shadow(200, 150, 90, 70, 40, 21);
  const ImageF big_test = soft_shadow(200, 150, 95, 72, 38, 22);
  const ImageF small_ref = soft_shadow(40, 30, 20, 15, 8, 23);
  const ImageF small_test = soft_shadow(40, 30, 21, 14, 9, 24);
  ImageU32 texels(200, 150, 1);
  for (size_t i = 0; i < texels.data.size(); ++i) texels.data[i] = uint32_t(i / 3);
  MetricScratch scratch;
  const auto fresh_big = fields(compute_metric(big_test, big_ref, &texels, nullptr));
  const auto fresh_small = fields(compute_metric(small_test, small_ref, nullptr, nullptr));
  EXPECT_EQ(fields(compute_metric(big_test, big_ref, &texels, nullptr, {}, &scratch)), fresh_big);
  EXPECT_EQ(fields(compute_metric(small_test, small_ref, nullptr, nullptr, {}, &scratch)),
            fresh_small);
  EXPECT_EQ(fields(compute_metric(big_test, big_ref, &texels, nullptr, {}, &scratch)), fresh_big);
}

TEST(ShadowMetric, BitIdenticalForAnyThreadCount) {
  const int saved = thread_count();
  const ImageF ref = soft_shadow(301, 203, 150, 100, 50, 11);
  const ImageF test = soft_shadow(301, 203, 153, 98, 47, 12);
  ImageU32 texels(301, 203, 1);
  for (int y = 0; y < 203; ++y)
    for (int x = 0; x < 301; ++x)
      texels.at(x, y) = (x + y) % 9 == 0 ? kNoTexel : uint32_t((y / 3) * 101 + x / 3);
  const Timings t{9.0, 4.0};
  MetricReport first{};
  for (const int n : {1, 2, 7}) {
    set_thread_count(n);
    const MetricReport r = compute_metric(test, ref, &texels, &t);
    if (n == 1) {
      first = r;
      continue;
    }
    const double a[] = {r.c10,        r.c50,   r.c90,    r.dark,        r.lit,
                        r.acne,       r.noise, r.detail, r.performance, r.fidelity,
                        r.aesthetics, r.total, r.ssim,   r.rmse,        r.psnr};
    const double b[] = {first.c10,         first.c50,      first.c90,        first.dark,
                        first.lit,         first.acne,     first.noise,      first.detail,
                        first.performance, first.fidelity, first.aesthetics, first.total,
                        first.ssim,        first.rmse,     first.psnr};
    EXPECT_EQ(std::memcmp(a, b, sizeof a), 0) << "threads " << n;
  }
  set_thread_count(saved);
  // The case is not trivial: the masks differ, so no score is simply 1.
  EXPECT_LT(first.c50, 1.0);
  EXPECT_LT(first.acne + first.noise, 2.0);
  EXPECT_LT(first.detail, 1.0);
}

}  // namespace
}  // namespace shadowlab
