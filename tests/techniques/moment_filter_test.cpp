// Moment filters against brute-force computations in long double, on the stiff inputs the
// design notes name: VSM variance near d = 1 (fp32 cancellation) and ESM with c = 500.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/isa.h"
#include "techniques/filters/moments_common/moment_filter.h"
#include "techniques/pipeline/texel_tiles.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Brute-force k×k clamp-to-edge window of (d, d²) in long double.
void window_moments(const std::vector<float>& d, int w, int h, int k, int x, int y,
                    long double& m1, long double& m2) {
  m1 = m2 = 0.0L;
  for (int j = -k / 2; j <= k / 2; ++j)
    for (int i = -k / 2; i <= k / 2; ++i) {
      const long double v = d[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))];
      m1 += v;
      m2 += v * v;
    }
  m1 /= (k * k);
  m2 /= (k * k);
}

// Depths 0.999 ± 1e-5: the true variance (~3e-11) is far below fp32's resolution of d² near 1
// (1.2e-7), so the fp32 form returns noise while the double filter with centred storage keeps
// 1e-3 relative accuracy, and the k = 3 centred float window its analysed 282·2^-24
// (techniques/filters/moments_common/centred_window3.h).
TEST(MomentFilter, VarianceNearFarPlaneSurvivesInDoubleNotInFp32) {
  for (const int k : {3, 5}) {
    const int w = 40, h = 30;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1e-5f, 1e-5f);
    std::vector<float> d(size_t(w * h));
    for (float& v : d) v = 0.999f + u(rng);
    std::vector<float> mean, var, m1, m2;
    filter_moments_double(d.data(), w, h, k, false, mean, var);
    filter_moments_fp32(d.data(), w, h, k, false, m1, m2);
    double worst_double = 0.0, worst_fp32 = 0.0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        long double e1, e2;
        window_moments(d, w, h, k, x, y, e1, e2);
        const double truth = double(e2 - e1 * e1);
        ASSERT_GT(truth, 1e-12);
        const size_t i = size_t(y * w + x);
        EXPECT_NEAR(mean[i], double(e1), 1e-7);
        worst_double = test::worst_of(worst_double, std::fabs(double(var[i]) - truth) / truth);
        worst_fp32 = test::worst_of(worst_fp32, std::fabs(double(m2[i] - m1[i] * m1[i]) - truth) / truth);
      }
    EXPECT_LT(worst_double, k == 3 ? 282.0 * std::ldexp(1.0, -24) : 1e-3) << "k " << k;
    EXPECT_GT(worst_fp32, 10.0);  // the naive form is off by orders of magnitude
  }
}

// ESM with c = 500 over depths spread across [0, 1]: exp(500·d) overflows fp32 (and e^500 is
// near double's limit); the log-space filter equals log(mean(exp(c·d))) computed by
// brute force in long double (range to e^11356), to float precision of c·z. The bound from the
// filter's float steps (docs/techniques/esm.md): each exponent c·(d − d_min) is rounded once to
// float (relative 2^-24, so up to c·2^-24 in every term's log, hence in the mean's), exp_wide and
// log_wide add at most 3e-7 and 2e-7, and the stored float rounds by half its ulp. Measured
// worst 2.7e-5 against a bound of 6.0e-5 at the largest values.
TEST(MomentFilter, EsmLogSpaceFilterIsFiniteAndExactAtCFiveHundred) {
  const int w = 24, h = 20, k = 5;
  const double c = 500.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> d(size_t(w * h));
  for (float& v : d) v = u(rng);
  d[5] = std::numeric_limits<float>::infinity();  // nothing seen: counts as 1
  EXPECT_TRUE(std::isinf(std::exp(float(c) * 0.5f)));  // the naive fp32 form overflows
  std::vector<float> out;
  filter_esm_log(d.data(), w, h, k, c, out);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      long double s = 0.0L;
      for (int j = -k / 2; j <= k / 2; ++j)
        for (int i = -k / 2; i <= k / 2; ++i) {
          float v = d[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))];
          if (!(v < 1.0f)) v = 1.0f;
          s += std::exp((long double)c * (long double)v);
        }
      const double truth = double(std::log(s / (k * k)));
      const float got = out[size_t(y * w + x)];
      ASSERT_TRUE(std::isfinite(got));
      const float tf = float(truth);
      const double half_ulp = 0.5 * double(std::nextafter(tf, INFINITY) - tf);
      EXPECT_NEAR(got, truth, c * 0x1p-24 + half_ulp + 5e-7) << x << "," << y;
    }
}

// The fixed-width kernels (k = 1..9, sums in registers, vectorized) against the runtime-k row
// loops, bit for bit, on images whose widths are not multiples of any vector length (and one
// that is: MSM's fused row then ends on a whole step, its last output line made of the step's
// last texels alone), with empty texels (+inf) and exact ties, at every compiled width and one
// runtime width.
// The fixed-width kernels (whichever ISA the filters pick) against the runtime-width loops.
void fixed_width_kernels_equal_the_runtime_width_loops() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.2f);  // > 1 and +inf: nothing seen
  for (const auto& [w, h] :
       {std::pair{37, 23}, std::pair{1030, 9}, std::pair{5, 40}, std::pair{64, 7}}) {
    std::vector<float> d(size_t(w) * size_t(h));
    for (float& v : d) v = u(rng);
    d[3] = std::numeric_limits<float>::infinity();
    d[d.size() - 1] = std::numeric_limits<float>::infinity();
    d[d.size() / 2] = d[d.size() / 2 + 1];
    // Flat columns at every row's start: windows of one depth, whose variance b − a² rounds to
    // a tiny negative or positive value, so the positive part is exercised in the kernels'
    // first (one-by-one) texels too.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < std::min(w, 14); ++x) d[size_t(y) * size_t(w) + size_t(x)] = 0.7f;
    for (int k : {1, 3, 5, 7, 9, 11}) {
      std::vector<float> mean, var, mean_o, var_o, esm, esm_o;
      filter_moments_double(d.data(), w, h, k, false, mean, var);
      filter_moments_double_oracle(d.data(), w, h, k, false, mean_o, var_o);
      filter_esm_log(d.data(), w, h, k, 200.0, esm);
      filter_esm_log_oracle(d.data(), w, h, k, 200.0, esm_o);
      ASSERT_EQ(mean.size(), d.size());
      ASSERT_EQ(esm.size(), d.size());
      EXPECT_EQ(std::memcmp(mean.data(), mean_o.data(), d.size() * 4), 0) << w << "x" << h << " k " << k;
      EXPECT_EQ(std::memcmp(var.data(), var_o.data(), d.size() * 4), 0) << w << "x" << h << " k " << k;
      // The slope moment (Krave) goes through the two-plane fixed kernels too.
      std::vector<float> smean, svar, smean_o, svar_o;
      filter_moments_double(d.data(), w, h, k, true, smean, svar);
      filter_moments_double_oracle(d.data(), w, h, k, true, smean_o, svar_o);
      EXPECT_EQ(std::memcmp(smean.data(), smean_o.data(), d.size() * 4), 0) << "slope k " << k;
      EXPECT_EQ(std::memcmp(svar.data(), svar_o.data(), d.size() * 4), 0) << "slope k " << k;
      // The interleaved storage of the VSM lookup holds the oracle's two planes, texel by texel
      // (with and without the slope moment; k = 11 runs the runtime-width loops).
      for (const bool slope : {false, true}) {
        std::vector<float> mv;
        filter_moments_double_interleaved(d.data(), w, h, k, slope, mv);
        ASSERT_EQ(mv.size(), 2 * d.size());
        const std::vector<float>& m_o = slope ? smean_o : mean_o;
        const std::vector<float>& v_o = slope ? svar_o : var_o;
        for (size_t i = 0; i < d.size(); ++i) {
          ASSERT_EQ(std::memcmp(&mv[2 * i], &m_o[i], 4), 0) << "interleaved mean " << i << " k " << k;
          ASSERT_EQ(std::memcmp(&mv[2 * i + 1], &v_o[i], 4), 0) << "interleaved var " << i << " k " << k;
        }
      }
      EXPECT_EQ(std::memcmp(esm.data(), esm_o.data(), d.size() * 4), 0) << w << "x" << h << " k " << k;
      std::vector<float> pm[4], pm_o[4];
      filter_power_moments(d.data(), w, h, k, pm);
      filter_power_moments_oracle(d.data(), w, h, k, pm_o);
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(std::memcmp(pm[c].data(), pm_o[c].data(), d.size() * 4), 0) << "msm " << c << " k " << k;
      std::vector<float> pmi;  // MSM's interleaved storage: the oracle's planes, texel by texel
      filter_power_moments_interleaved(d.data(), w, h, k, pmi);
      ASSERT_EQ(pmi.size(), 4 * d.size());
      for (size_t i = 0; i < d.size(); ++i)
        for (int c = 0; c < 4; ++c)
          ASSERT_EQ(std::memcmp(&pmi[4 * i + size_t(c)], &pm_o[c][i], 4), 0)
              << "msm interleaved " << i << " moment " << c << " k " << k;
      for (const double sign : {1.0, -1.0}) {
        std::vector<float> wm, wv, wm_o, wv_o;
        filter_warped_moments(d.data(), w, h, k, 40.0, sign, wm, wv);
        filter_warped_moments_oracle(d.data(), w, h, k, 40.0, sign, wm_o, wv_o);
        EXPECT_EQ(std::memcmp(wm.data(), wm_o.data(), d.size() * 4), 0) << "evsm k " << k;
        EXPECT_EQ(std::memcmp(wv.data(), wv_o.data(), d.size() * 4), 0) << "evsm k " << k;
        // EVSM's interleaved storage: the oracle's planes, texel by texel, at stride 2 and in
        // both halves of stride 4 (the other half's slots left as they were: here 7).
        for (const auto& [stride, first] : {std::pair{2, 0}, std::pair{4, 0}, std::pair{4, 2}}) {
          std::vector<float> wmv(size_t(stride) * d.size(), 7.0f);
          filter_warped_moments_interleaved(d.data(), w, h, k, 40.0, sign, stride, first, wmv);
          ASSERT_EQ(wmv.size(), size_t(stride) * d.size());
          for (size_t i = 0; i < d.size(); ++i) {
            const size_t at = size_t(stride) * i + size_t(first);
            ASSERT_EQ(std::memcmp(&wmv[at], &wm_o[i], 4), 0) << "evsm interleaved " << i;
            ASSERT_EQ(std::memcmp(&wmv[at + 1], &wv_o[i], 4), 0) << "evsm interleaved " << i;
            if (stride == 4) {
              ASSERT_EQ(wmv[size_t(stride) * i + size_t(2 - first)], 7.0f);
            }
          }
        }
      }
    }
  }
}

// For every table this CPU has (techniques/filters/moments_common/moment_rows.h; SHADOWLAB_ISA=avx2 and
// SHADOWLAB_SCALAR=1 choose the narrower ones): the filters through that table against the
// oracles, which run the scalar table's runtime-width loops.
TEST(MomentFilter, FixedWidthKernelsEqualTheRuntimeWidthLoopsBitForBit) {
  for (const Isa isa : cpu_isas()) {
    const ScopedIsa guard(isa);
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(process_isa(), isa);
    fixed_width_kernels_equal_the_runtime_width_loops();
  }
}

// MSM's four power moments are the window means of d, d², d³, d⁴ (long double brute force,
// "nothing seen" as 1). The filter sums in float: a window mean of k² positive terms carries at
// most (2k + 2) roundings of u = 2^-24 to first order (two in d⁴, k − 1 in each of the two
// passes, the × 1/k² and 1/k² itself); the bound is half that, (k + 1)·u relative (2.4e-7 at
// k = 3, 7.2e-7 at k = 11), where the measured worst cases are 1.0e-7 and 2.7e-7.
TEST(MomentFilter, PowerMomentsAreTheWindowMeans) {
  const int w = 23, h = 17;
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(0.0f, 1.1f);
  std::vector<float> d(size_t(w * h));
  for (float& v : d) v = u(rng);
  d[7] = std::numeric_limits<float>::infinity();
  for (const int k : {3, 11}) {
    const double bound = double(k + 1) * 0x1p-24;
    std::vector<float> pm[4];
    filter_power_moments(d.data(), w, h, k, pm);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        long double m[4] = {0.0L, 0.0L, 0.0L, 0.0L};
        for (int j = -k / 2; j <= k / 2; ++j)
          for (int i = -k / 2; i <= k / 2; ++i) {
            const float v = d[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w) +
                              size_t(std::clamp(x + i, 0, w - 1))];
            const long double t = v < 1.0f ? v : 1.0L;
            for (int c = 0; c < 4; ++c) m[c] += std::pow(t, c + 1) / (k * k);
          }
        for (int c = 0; c < 4; ++c)
          ASSERT_NEAR(pm[c][size_t(y * w + x)], double(m[c]), bound * double(m[c]) + 1e-12)
              << "k " << k << " moment " << c + 1 << " at " << x << "," << y;
      }
  }
}

// The max filter is the brute-force window maximum.
TEST(MomentFilter, MaxFilterIsTheWindowMaximum) {
  const int w = 17, h = 11, k = 3;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> d(size_t(w * h));
  for (float& v : d) v = u(rng);
  std::vector<float> out;
  FilterScratch scratch;
  filter_max(d.data(), w, h, k, out, scratch);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float m = 0.0f;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
          m = std::max(m, d[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))]);
      EXPECT_EQ(out[size_t(y * w + x)], m);
    }
}

}  // namespace
}  // namespace shadowlab

namespace shadowlab {
namespace {

// Bits of texel i's `stride` floats at `at` of both arrays are equal.
bool same_texel(const std::vector<float>& a, const std::vector<float>& b, size_t at, int n) {
  return std::memcmp(&a[at], &b[at], size_t(n) * 4) == 0;
}

// Every filter run with tiles (techniques/pipeline/texel_tiles.h) writes, on the texels of the needed
// tiles, the whole image's bits, and leaves every other texel as it was (here 7): spans at the
// image's left and right edges, in the partial last column and row of tiles, a lone tile, and a
// tile row with no span; box widths 1, 3, 5 and 11 (k = 11: the runtime-width loops), the slope
// moment, the oracles.
TEST(MomentFilter, TiledFiltersWriteTheWholeImageBitsOnTheirTilesOnly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.2f);
  const int w = 100, h = 70;  // 4 × 3 tiles of 32, the last column and row partial
  std::vector<float> d(size_t(w) * size_t(h));
  for (float& v : d) v = u(rng);
  d[7] = std::numeric_limits<float>::infinity();
  FaceTiles tiles;
  tiles.tiles_x = 4;
  tiles.tiles_y = 3;
  tiles.need = {1, 0, 0, 1,  //
                0, 1, 0, 0,  //
                1, 1, 1, 1};
  auto needed = [&](size_t i) {
    const int x = int(i % size_t(w)), y = int(i / size_t(w));
    return tiles.need[size_t(y / 32) * 4 + size_t(x / 32)] != 0;
  };
  float face_min = std::numeric_limits<float>::infinity();
  for (const float v : d) face_min = std::min(face_min, v);
  size_t checked = 0;
  // Runs fn(out, tiles) into fresh planes of `stride` floats per texel, filled with 7, with
  // and without tiles, and compares texel by texel.
  auto check = [&](const char* what, int stride, const auto& fn) {
    SCOPED_TRACE(what);
    std::vector<float> whole(size_t(stride) * d.size(), 7.0f), tiled = whole;
    fn(whole, nullptr);
    fn(tiled, &tiles);
    ASSERT_EQ(whole.size(), tiled.size());
    for (size_t i = 0; i < d.size(); ++i) {
      if (needed(i)) {
        ASSERT_TRUE(same_texel(whole, tiled, size_t(stride) * i, stride)) << "texel " << i;
      } else {
        for (int c = 0; c < stride; ++c) ASSERT_EQ(tiled[size_t(stride) * i + size_t(c)], 7.0f) << i;
      }
    }
    ++checked;
  };
  for (const int k : {1, 3, 5, 11}) {
    SCOPED_TRACE(k);
    for (const bool slope : {false, true}) {
      check("vsm interleaved", 2, [&](std::vector<float>& o, const FaceTiles* t) {
        filter_moments_double_interleaved(d.data(), w, h, k, slope, o, t);
      });
      for (const bool oracle : {false, true}) {
        auto planes = [&](std::vector<float>& o, const FaceTiles* t) {
          std::vector<float> m(d.size(), 7.0f), v(d.size(), 7.0f);
          if (oracle)
            filter_moments_double_oracle(d.data(), w, h, k, slope, m, v, t);
          else
            filter_moments_double(d.data(), w, h, k, slope, m, v, t);
          for (size_t i = 0; i < d.size(); ++i) {
            o[2 * i] = m[i];
            o[2 * i + 1] = v[i];
          }
        };
        check(oracle ? "vsm oracle" : "vsm planes", 2, planes);
      }
    }
    check("esm", 1, [&](std::vector<float>& o, const FaceTiles* t) {
      filter_esm_log(d.data(), w, h, k, 200.0, o, t);
    });
    check("esm oracle", 1, [&](std::vector<float>& o, const FaceTiles* t) {
      filter_esm_log_oracle(d.data(), w, h, k, 200.0, o, t);
    });
    // The render's minimum instead of the filter's own pass: the same bits.
    check("esm face_min", 1, [&](std::vector<float>& o, const FaceTiles* t) {
      if (t) {
        filter_esm_log(d.data(), w, h, k, 200.0, o, t, &face_min);
      } else {
        filter_esm_log(d.data(), w, h, k, 200.0, o);
      }
    });
    for (const double sign : {1.0, -1.0}) {
      check("evsm stride 4", 4, [&](std::vector<float>& o, const FaceTiles* t) {
        filter_warped_moments_interleaved(d.data(), w, h, k, 40.0, sign, 4, sign > 0 ? 0 : 2, o, t);
      });
      check("evsm oracle", 2, [&](std::vector<float>& o, const FaceTiles* t) {
        std::vector<float> m(d.size(), 7.0f), v(d.size(), 7.0f);
        filter_warped_moments_oracle(d.data(), w, h, k, 40.0, sign, m, v, t);
        for (size_t i = 0; i < d.size(); ++i) {
          o[2 * i] = m[i];
          o[2 * i + 1] = v[i];
        }
      });
    }
    check("msm interleaved", 4, [&](std::vector<float>& o, const FaceTiles* t) {
      filter_power_moments_interleaved(d.data(), w, h, k, o, t);
    });
    check("msm oracle", 4, [&](std::vector<float>& o, const FaceTiles* t) {
      std::vector<float> pm[4];
      for (auto& v : pm) v.assign(d.size(), 7.0f);
      filter_power_moments_oracle(d.data(), w, h, k, pm, t);
      for (size_t i = 0; i < d.size(); ++i)
        for (int c = 0; c < 4; ++c) o[4 * i + size_t(c)] = pm[c][i];
    });
  }
  EXPECT_EQ(checked, size_t(4 * (2 * 3 + 3 + 2 * 2 + 2)));
}

}  // namespace
}  // namespace shadowlab
