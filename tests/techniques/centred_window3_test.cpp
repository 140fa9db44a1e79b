// The centred 3 × 3 window of VSM's and EVSM's k = 3 filter (techniques/filters/moments_common/centred_window3.h):
// its vector kernels against its scalar loop bit for bit, and its float mean and variance
// against the same nine values' moments in long double, within the header's analysed bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "core/isa.h"
#include "techniques/filters/moments_common/centred_window3.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Three extended input rows of n + 2 floats each.
struct Rows {
  int n;
  std::vector<float> r[3];
};

// Rows of the kinds the filters feed: uniform depths, flat runs (every δ 0), ties, values
// near 1, and EVSM's warps up to ±e^44.
Rows make_rows(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Rows rows{n, {}};
  for (int j = 0; j < 3; ++j) {
    rows.r[j].resize(size_t(n) + 2);
    for (int x = 0; x < n + 2; ++x) {
      const float v = u(rng);
      switch ((x / 7 + j + int(seed)) % 5) {
        case 0: rows.r[j][size_t(x)] = v; break;
        case 1: rows.r[j][size_t(x)] = 0.75f; break;                      // flat
        case 2: rows.r[j][size_t(x)] = 0.999f + 1e-5f * (v - 0.5f); break;  // near the far plane
        case 3: rows.r[j][size_t(x)] = std::exp(44.0f * (2.0f * v - 1.0f)); break;
        default: rows.r[j][size_t(x)] = -std::exp(-44.0f * (2.0f * v - 1.0f)); break;
      }
    }
  }
  return rows;
}

// Every kernel this CPU has against the scalar loop, for each output layout (two planes,
// interleaved pairs at every offset within a cache line, EVSM4's stride 4), at lengths around
// the vector widths.
TEST(CentredWindow3, VectorKernelsGiveTheScalarBits) {
  std::vector<Isa> isas = cpu_isas();
  isas.erase(isas.begin());  // the scalar table: the oracle
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  int compared = 0;
  for (const int n : {1, 7, 8, 9, 15, 16, 17, 31, 33, 100, 1030}) {
    const Rows rows = make_rows(n, uint32_t(n));
    const float* r0 = rows.r[0].data();
    const float* r1 = rows.r[1].data();
    const float* r2 = rows.r[2].data();
    for (const int stride : {1, 2, 4}) {
      for (int offset = 0; offset < (stride == 2 ? 8 : 1); ++offset) {
        // Planes: mean and variance in two arrays; else one array, variance after the mean.
        const size_t len = size_t(stride) * size_t(n) + 64;
        std::vector<float> want(2 * len, -7.0f), got(2 * len, -7.0f);
        auto run = [&](Isa isa, std::vector<float>& out) {
          float* const mean = out.data() + offset;
          float* const var = stride == 1 ? out.data() + len : mean + 1;
          centred_window3_kernels(isa).row(r0, r1, r2, n, mean, var, stride);
        };
        run(Isa::scalar, want);
        for (const Isa isa : isas) {
          std::fill(got.begin(), got.end(), -7.0f);
          run(isa, got);
          ASSERT_EQ(std::memcmp(want.data(), got.data(), want.size() * sizeof(float)), 0)
              << "n " << n << " stride " << stride << " offset " << offset << " isa "
              << isa_name(isa);
          ++compared;
        }
      }
    }
  }
  EXPECT_GE(compared, 11 * 10);
}

// The nine values' mean and variance in long double.
void exact_moments(const Rows& rows, int x, long double& mean, long double& var) {
  long double s1 = 0.0L, s2 = 0.0L;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const long double v = rows.r[j][size_t(x + i)];
      s1 += v;
      s2 += v * v;
    }
  mean = s1 / 9.0L;
  long double c = 0.0L;  // the centred second moment, free of cancellation
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const long double d = rows.r[j][size_t(x + i)] - mean;
      c += d * d;
    }
  var = c / 9.0L;
}

// Windows whose centre differs from its eight equal neighbours (the cancellation the header's
// 1/9 allows, at its worst: the variance is exactly 1/9 of Σ(δ/3)²), and random ones.
Rows spike_rows(int n, uint32_t seed, float base, float spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Rows rows{n, {}};
  for (int j = 0; j < 3; ++j) rows.r[j].assign(size_t(n) + 2, base);
  for (int x = 1; x < n + 1; x += 2) rows.r[1][size_t(x)] = base + spread * u(rng);
  return rows;
}

// The float mean and variance against long double, with u = 2^-24 and σ² the exact variance:
// the mean within u·|mean| + 26u·σ and the variance within 282u·σ² (the header's first-order
// bounds: docs/techniques/vsm.md, Precision, derives both).
TEST(CentredWindow3, MeanAndVarianceWithinTheirAnalysedBounds) {
  const long double u = std::ldexp(1.0L, -24);
  long double worst_mean = 0.0L, worst_var = 0.0L;
  int checked = 0;
  std::vector<Rows> cases;
  for (uint32_t s = 0; s < 40; ++s) cases.push_back(make_rows(200, 100 + s));
  for (uint32_t s = 0; s < 40; ++s) {
    cases.push_back(spike_rows(200, s, 0.6f, 1e-4f));
    cases.push_back(spike_rows(200, s + 40, 0.999f, 1e-5f));
    cases.push_back(spike_rows(200, s + 80, 3.0e17f, 1e17f));
  }
  for (const Rows& rows : cases) {
    std::vector<float> mean(size_t(rows.n)), var(size_t(rows.n));
    centred_window3_kernels(Isa::scalar)
        .row(rows.r[0].data(), rows.r[1].data(), rows.r[2].data(), rows.n, mean.data(), var.data(), 1);
    for (int x = 0; x < rows.n; ++x) {
      long double m, v;
      exact_moments(rows, x, m, v);
      ASSERT_TRUE(std::isfinite(mean[size_t(x)]) && std::isfinite(var[size_t(x)])) << x;
      const long double sigma = std::sqrt(v);
      const long double em = std::fabs(mean[size_t(x)] - m) / (u * (std::fabs(m) + 26.0L * sigma));
      worst_mean = test::worst_of(worst_mean, em);
      if (v > 0.0L) {
        worst_var = test::worst_of(worst_var, std::fabs(var[size_t(x)] - v) / (282.0L * u * v));
      } else {
        EXPECT_EQ(var[size_t(x)], 0.0f) << x;
      }
      ++checked;
    }
  }
  std::printf("worst mean error %.3Lg and variance error %.3Lg of their bounds\n", worst_mean,
              worst_var);
  EXPECT_LE(worst_mean, 1.0L);
  EXPECT_LE(worst_var, 1.0L);
  EXPECT_GE(checked, 160 * 200);
}

}  // namespace
}  // namespace shadowlab
