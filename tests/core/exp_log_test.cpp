// exp_d and log_d (core/exp_log.h) against long double, and the vector forms of every set this
// CPU runs (core/exp_log_avx2.h, exp_log_avx512.h, and loops vectorized for each set) against the
// scalar calls, bit for bit.
#include "core/exp_log.h"
#include "core/isa.h"
#include "exp_log_lanes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Scalar calls: noinline keeps them out of any vectorized loop.
__attribute__((noinline)) double exp_one(double x) { return exp_d(x); }
__attribute__((noinline)) double log_one(double x) { return log_d(x); }
__attribute__((noinline)) float expf_one(float x) { return exp_f(x); }
__attribute__((noinline)) double expw_one(float x) { return exp_wide(x); }
__attribute__((noinline)) double logw_one(double x) { return log_wide(x); }

// The vector tables this CPU runs (tests/core/exp_log_lanes.h): every set but scalar.
std::vector<const test::ExpLogLanes*> vector_tables() {
  std::vector<const test::ExpLogLanes*> out;
  for (const Isa isa : cpu_isas())
    if (const test::ExpLogLanes* t = test::exp_log_lanes(isa)) out.push_back(t);
  return out;
}

// Distance in units of the last place of the exact value (long double).
double ulps(double got, long double exact) {
  const double e = double(exact);
  return double(std::fabs((long double)got - exact)) / (std::nextafter(std::fabs(e), INFINITY) - std::fabs(e));
}

TEST(ExpLog, WithinTwoUlpOfLongDouble) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> ux(-700.0, 700.0), ul(-690.0, 700.0);
  double worst_exp = 0.0, worst_log = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = i < 4 ? double(i) * 0.5 : ux(rng);
    worst_exp = test::worst_of(worst_exp, ulps(exp_one(x), std::exp((long double)x)));
    const double y = std::exp(ul(rng));  // log's arguments over [e^-690, e^700]
    worst_log = test::worst_of(worst_log, ulps(log_one(y), std::log((long double)y)));
  }
  // Arguments near 1 from both sides (small results: no cancellation allowed) and at the
  // mantissa steps.
  for (int i = 1; i < 20000; ++i) {
    const double y = i % 2 ? 1.0 + 1e-7 * i : 1.0 - 1e-7 * i;
    worst_log = test::worst_of(worst_log, ulps(log_one(y), std::log((long double)y)));
    const double z = std::ldexp(1.0 + double(i % 16) / 16.0, i % 40 - 20) * (1.0 + 1e-13 * (i % 7));
    worst_log = test::worst_of(worst_log, ulps(log_one(z), std::log((long double)z)));
  }
  // Exact points.
  EXPECT_EQ(exp_one(0.0), 1.0);
  EXPECT_EQ(log_one(1.0), 0.0);
  EXPECT_LE(worst_exp, 2.0);
  EXPECT_LE(worst_log, 2.0);
  RecordProperty("worst_exp_ulp", std::to_string(worst_exp));
  RecordProperty("worst_log_ulp", std::to_string(worst_log));
}

// Float ulps of the exact value.
double ulps_f(float got, long double exact) {
  const float e = float(exact);
  return double(std::fabs((long double)got - exact)) / double(std::nextafter(std::fabs(e), INFINITY) - std::fabs(e));
}

TEST(ExpLog, FloatExpWithinTwoUlpOfLongDouble) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-87.0f, 88.0f);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const float x = u(rng);
    worst = test::worst_of(worst, ulps_f(expf_one(x), std::exp((long double)x)));
  }
  EXPECT_EQ(expf_one(0.0f), 1.0f);
  EXPECT_LE(worst, 2.0);
  RecordProperty("worst_expf_ulp", std::to_string(worst));
}

// exp_wide and log_wide (the ESM filter's float-precision pair, whose range is double's) against
// long double. exp_wide: float x over the ESM filter's [0, 700] and the negative side, grid
// points at multiples of ln2 (the reduction's rounding from either side) and the ends; its
// error is exp_f's (2 float ulps, 2.4e-7 relative) plus the reduction's for |n| up to 1,010
// (n·ln2's low part, ~2e-8): 3e-7. log_wide: arguments over [1, e^700] (the filter's: box means
// of e^(c·(d − d_min)) >= 1), near 1 from both sides, at the fold (mantissas just below and
// above 1.5) and over [e^-690, 1]; its error is m's rounding to float (6e-8 relative, so
// absolute in ln m), the series in float (|ln m| <= 0.41: ~1e-7) and e·ln2 in double: 2e-7
// absolute. Measured: docs/techniques/esm.md.
TEST(ExpLog, WideExpAndLogHoldFloatPrecisionOverDoublesRange) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<float> ux(-700.0f, 700.0f);
  std::uniform_real_distribution<double> ul(0.0, 700.0), ul_neg(-690.0, 0.0);
  double worst_exp = 0.0, worst_log = 0.0;
  auto check_exp = [&](float x) {
    const long double exact = std::exp((long double)x);
    worst_exp = test::worst_of(worst_exp, double(std::fabs((long double)expw_one(x) / exact - 1.0L)));
  };
  auto check_log = [&](double y) {
    worst_log = test::worst_of(worst_log, double(std::fabs((long double)logw_one(y) - std::log((long double)y))));
  };
  for (int i = 0; i < 200000; ++i) {
    check_exp(ux(rng));
    check_log(std::exp(i % 4 ? ul(rng) : ul_neg(rng)));
  }
  for (int n = -1000; n <= 1000; ++n)
    for (const float f : {-0.5f, -0.49f, 0.0f, 0.49f, 0.5f})
      check_exp(float((double(n) + double(f)) * 0.6931471805599453));
  for (const float x : {0.0f, 1e-30f, -1e-30f, 700.0f, -700.0f, 88.7f, 89.0f}) check_exp(x);
  for (int i = 1; i < 20000; ++i) {
    check_log(i % 2 ? 1.0 + 1e-7 * i : 1.0 - 1e-7 * i);
    const double fold = std::ldexp(1.5, i % 80 - 20);
    check_log(i % 2 ? std::nextafter(fold, 0.0) : fold);
  }
  EXPECT_EQ(expw_one(0.0f), 1.0);
  EXPECT_EQ(logw_one(1.0), 0.0);
  EXPECT_LE(worst_exp, 3e-7);
  EXPECT_LE(worst_log, 2e-7);
  char text[64];
  std::snprintf(text, sizeof text, "%.3g relative, log %.3g absolute", worst_exp, worst_log);
  RecordProperty("worst_wide_exp_and_log", text);
}

// exp_wide8 / exp_wide16 and log_wide8 / log_wide16 give the scalar calls' bits, lane for lane
// (each half of the pair in its own place): grid and random exponents as above, and log
// arguments at every power of two, both sides of the fold and just around 1.
TEST(ExpLog, IntrinsicWideExpsAndLogsGiveTheScalarBits) {
  const auto tables = vector_tables();
  if (tables.empty()) GTEST_SKIP() << "no vector set on this CPU";
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<float> ux(-700.0f, 700.0f);
  std::uniform_real_distribution<double> ul(-690.0, 700.0);
  for (int i = 0; i < 100000; i += 16) {
    float x[16];
    double y[16], ev[16], lv[16];
    for (int k = 0; k < 16; ++k) {
      const int t = i + k;
      x[k] = t < 4096 ? float(double(t - 2048) * 0.6931471805599453 / 3.0) : ux(rng);
      y[k] = t < 160  ? std::ldexp(t % 2 ? std::nextafter(1.5, 0.0) : 1.5, t / 2 - 40)
             : t < 192 ? std::nextafter(1.0, t % 2 ? 2.0 : 0.0) * (1.0 + 1e-9 * (t - 160))
             : t < 256 ? std::ldexp(1.0, t - 224)
                       : std::exp(ul(rng));
    }
    for (const test::ExpLogLanes* lanes : tables) {
      lanes->exp_wide(x, ev);
      lanes->log_wide(y, lv);
      for (int k = 0; k < 16; ++k) {
        const double e = expw_one(x[k]), l = logw_one(y[k]);
        ASSERT_EQ(std::memcmp(&ev[k], &e, 8), 0) << isa_name(lanes->isa) << " exp_wide " << x[k];
        ASSERT_EQ(std::memcmp(&lv[k], &l, 8), 0) << isa_name(lanes->isa) << " log_wide " << y[k];
      }
    }
  }
}

// exp_d4 (AVX2: the table by a gather) and exp_d8 (AVX-512: by a two-register permute) give
// exp_d's bits, negative arguments included (EVSM's negative warp), every table index and both
// signs of the exponent: 2^(j/16) at j = 0..15 are hit by x = (16q + j)·ln2/16.
TEST(ExpLog, IntrinsicExpGivesTheScalarBits) {
  const auto tables = vector_tables();
  if (tables.empty()) GTEST_SKIP() << "no vector set on this CPU";
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-700.0, 700.0);
  for (int i = 0; i < 100000; i += 16) {
    double x[16], y[16];
    for (int k = 0; k < 16; ++k)
      x[k] = i < 512 ? double(i + k - 256) * 0.6931471805599453 / 16.0 : u(rng);
    for (const test::ExpLogLanes* lanes : tables) {
      lanes->exp_d(x, y);
      for (int k = 0; k < 16; ++k) {
        const double one = exp_one(x[k]);
        ASSERT_EQ(std::memcmp(&y[k], &one, 8), 0) << isa_name(lanes->isa) << " " << x[k];
      }
    }
  }
}

// exp_f8 (AVX2) and exp_f16 (AVX-512) give exp_f's bits over its range: random arguments, and a
// grid of ln2/24 steps over [-59, 59] (both signs: EVSM's negative warp; and the reduction's
// rounding to the nearest multiple of ln2 from either side).
TEST(ExpLog, IntrinsicFloatExpsGiveTheScalarBits) {
  const auto tables = vector_tables();
  if (tables.empty()) GTEST_SKIP() << "no vector set on this CPU";
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-87.0f, 88.0f);
  size_t checked = 0;
  for (int i = 0; i < 200000; i += 16) {
    float x[16], y[16];
    for (int k = 0; k < 16; ++k)
      x[k] = i < 4096 ? float(i + k - 2048) * 0.6931471805599453f / 24.0f : u(rng);
    for (const test::ExpLogLanes* lanes : tables) {
      lanes->exp_f(x, y);
      for (int k = 0; k < 16; ++k) {
        const float one = expf_one(x[k]);
        ASSERT_EQ(std::memcmp(&y[k], &one, 4), 0) << isa_name(lanes->isa) << " exp_f " << x[k];
      }
    }
    checked += 16;
  }
  EXPECT_EQ(checked, 200000u);
}

// log_d4 and log_d8 give log_d's bits: every mantissa step (both sides of the fold at 1.5),
// arguments just below and above 1 and powers of two, and random ones over [e^-690, e^700].
TEST(ExpLog, IntrinsicLogsGiveTheScalarBits) {
  const auto tables = vector_tables();
  if (tables.empty()) GTEST_SKIP() << "no vector set on this CPU";
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-690.0, 700.0);
  for (int i = 0; i < 100000; i += 16) {
    double x[16], y[16];
    for (int k = 0; k < 16; ++k) {
      const int t = i + k;
      x[k] = t < 64 ? std::ldexp(1.0 + double(t % 16) / 16.0, t / 16 - 2)  // steps, octaves
             : t < 80 ? std::nextafter(1.0, t % 2 ? 2.0 : 0.0) * (1.0 + 1e-9 * (t - 64))
                      : std::exp(u(rng));
    }
    for (const test::ExpLogLanes* lanes : tables) {
      lanes->log_d(x, y);
      for (int k = 0; k < 16; ++k) {
        const double one = log_one(x[k]);
        ASSERT_EQ(std::memcmp(&y[k], &one, 8), 0) << isa_name(lanes->isa) << " " << x[k];
      }
    }
  }
}

// The scalar calls in loops vectorized for each set (the ESM filter's kind of loop).
TEST(ExpLog, VectorizedLoopsGiveTheScalarBits) {
  const auto tables = vector_tables();
  if (tables.empty()) GTEST_SKIP() << "no vector set on this CPU";
  for (const test::ExpLogLanes* lanes : tables) {
    SCOPED_TRACE(isa_name(lanes->isa));
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 700.0);
    const int n = 4099;  // not a multiple of any vector width
    std::vector<double> x(n), y(n), z(n);
    for (double& v : x) v = u(rng);
    lanes->exp_loop(x.data(), y.data(), n);
    for (int i = 0; i < n; ++i)
      ASSERT_EQ(std::memcmp(&y[i], &(z[i] = exp_one(x[i])), 8), 0) << x[i];
    for (double& v : x) v = std::exp(u(rng));
    lanes->log_loop(x.data(), y.data(), n);
    for (int i = 0; i < n; ++i)
      ASSERT_EQ(std::memcmp(&y[i], &(z[i] = log_one(x[i])), 8), 0) << x[i];
    std::uniform_real_distribution<float> uf(-87.0f, 88.0f);
    std::vector<float> xf(n), yf(n);
    for (float& v : xf) v = uf(rng);
    lanes->expf_loop(xf.data(), yf.data(), n);
    for (int i = 0; i < n; ++i) {
      const float one = expf_one(xf[i]);
      ASSERT_EQ(std::memcmp(&yf[i], &one, 4), 0) << xf[i];
    }
  }
}

// log_split_f: x = 2^e · m exactly with m in [0.75, 1.5), checked in double (exact for these
// values) on both sides of every binade's 1.5 and 1 points from 2^-126 up and on random
// positive normal floats; its vector forms give its m and e in every lane.
TEST(ExpLog, FloatLogSplitIsExactAndItsLanesAgree) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<uint32_t> bits(0x00800000u, 0x7F7FFFFFu);
  std::vector<float> xs;
  for (int b = -126; b <= 127; ++b)
    for (const float f : {1.0f, 1.5f}) {
      const float v = std::ldexp(f, b);
      if (std::isinf(v)) continue;
      xs.push_back(v);
      if (std::nextafter(v, 0.0f) >= std::numeric_limits<float>::min())
        xs.push_back(std::nextafter(v, 0.0f));
      xs.push_back(std::nextafter(v, INFINITY));
    }
  while (xs.size() % 16 != 0 || xs.size() < 20000) xs.push_back(std::bit_cast<float>(bits(rng)));
  const auto tables = vector_tables();
  for (size_t i = 0; i < xs.size(); i += 16) {
    float mv[2][16];
    int32_t ev[2][16];
    for (size_t t = 0; t < tables.size(); ++t) tables[t]->log_split_f(&xs[i], mv[t], ev[t]);
    for (int k = 0; k < 16; ++k) {
      const float x = xs[i + size_t(k)];
      int32_t e;
      const float m = log_split_f(x, e);
      ASSERT_GE(m, 0.75f) << x;
      ASSERT_LT(m, 1.5f) << x;
      ASSERT_EQ(std::ldexp(double(m), e), double(x)) << x;
      for (size_t t = 0; t < tables.size(); ++t) {
        ASSERT_EQ(std::memcmp(&mv[t][k], &m, 4), 0) << isa_name(tables[t]->isa) << " " << x;
        ASSERT_EQ(ev[t][k], e) << isa_name(tables[t]->isa) << " " << x;
      }
    }
  }
}

}  // namespace
}  // namespace shadowlab
