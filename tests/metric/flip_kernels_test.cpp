// metric/flip_kernels.h: every table this CPU runs against the scalar table, byte for byte, the
// scalar rows against their definitions, the vector power against exp_d(p·log_d(x)) with
// power()'s selects, and the whole FLIP map of every process set against the scalar one's.
#include "metric/flip_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "core/exp_log.h"
#include "core/isa.h"
#include "metric/flip.h"

namespace shadowlab {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  // Length 0 compares nothing (memcmp must not get the empty vectors' null pointers).
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Lengths 0..40 (every tail of the 16-column blocks and of the vectors) and 9 taps.
TEST(FlipKernels, EveryTablesRowsGiveTheScalarBits) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const int taps = 9, width = 40;
  std::vector<std::vector<double>> rows(taps, std::vector<double>(width));
  std::vector<const double*> ptrs;
  for (auto& r : rows) {
    for (double& v : r) v = u(rng);
    ptrs.push_back(r.data());
  }
  std::vector<double> k(taps);
  for (double& v : k) v = u(rng);
  const FlipKernels& scalar = flip_kernels(Isa::scalar);
  for (int n = 0; n <= width; ++n) {
    // The scalar rows against their definitions: sums from 0 in tap order; dst + c·src.
    std::vector<double> want(static_cast<size_t>(n), 0.0);
    std::vector<double> want_axpy(rows[1].begin(), rows[1].begin() + n);
    for (int x = 0; x < n; ++x) {
      double a = 0.0;
      for (int j = 0; j < taps; ++j) a += k[size_t(j)] * rows[size_t(j)][size_t(x)];
      want[size_t(x)] = a;
      want_axpy[size_t(x)] += 0.375 * rows[0][size_t(x)];
    }
    for (const Isa isa : cpu_isas()) {
      const FlipKernels& t = flip_kernels(isa);
      ASSERT_EQ(t.isa, isa);
      std::vector<double> got(static_cast<size_t>(n), -1.0);
      std::vector<double> got_axpy(rows[1].begin(), rows[1].begin() + n);
      t.weighted_rows(ptrs.data(), k.data(), taps, n, got.data());
      t.axpy(0.375, rows[0].data(), n, got_axpy.data());
      EXPECT_TRUE(same_bits(got, want)) << isa_name(isa) << " weighted_rows n " << n;
      EXPECT_TRUE(same_bits(got_axpy, want_axpy)) << isa_name(isa) << " axpy n " << n;
    }
  }
  EXPECT_EQ(scalar.power, nullptr);
}

// x^p as flip.cpp's power() defines it: 0 below 2^-1000 (p > 0), 1 for p = 0.
double power_def(double x, double p) {
  if (p == 0.0) return 1.0;
  return x < 0x1p-1000 ? 0.0 : exp_d(p * log_d(x));
}

TEST(FlipKernels, VectorPowerGivesPowersBits) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 50.0), up(0.0, 3.0);
  const size_t n = 203;
  std::vector<double> x(n), p(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = i % 17 == 0 ? 0.0 : i % 19 == 0 ? 0x1p-1010 : ux(rng);
    p[i] = i % 13 == 0 ? 0.0 : up(rng);
  }
  for (const Isa isa : cpu_isas()) {
    const FlipKernels& t = flip_kernels(isa);
    if (!t.power) continue;
    for (const bool per_value : {false, true}) {
      std::vector<double> got(n, -1.0);
      const size_t done = t.power(x.data(), per_value ? p.data() : nullptr, 1.0 / 3.0, n,
                                  got.data());
      const size_t lanes = isa == Isa::avx512 ? 8 : 4;
      EXPECT_EQ(done, n - n % lanes) << isa_name(isa);
      for (size_t i = 0; i < done; ++i) {
        const double want = power_def(x[i], per_value ? p[i] : 1.0 / 3.0);
        ASSERT_EQ(std::memcmp(&got[i], &want, 8), 0) << isa_name(isa) << " x " << x[i];
      }
      for (size_t i = done; i < n; ++i) EXPECT_EQ(got[i], -1.0) << "wrote past its vectors";
    }
  }
}

// Two grey masks and two colour images: FLIP's map under every set this CPU runs is the scalar
// set's, byte for byte.
TEST(FlipKernels, FlipMapOfEverySetIsTheScalarSets) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const int channels : {1, 3}) {
    ImageF a(61, 43, channels), b(61, 43, channels);
    for (float& v : a.data) v = u(rng);
    for (size_t i = 0; i < b.data.size(); ++i) b.data[i] = i % 7 ? a.data[i] : u(rng);
    ImageF want;
    {
      ScopedIsa scalar(Isa::scalar);
      want = flip_error_map(a, b);
    }
    for (const Isa isa : cpu_isas()) {
      ScopedIsa scoped(isa);
      const ImageF got = flip_error_map(a, b);
      ASSERT_EQ(got.data.size(), want.data.size());
      EXPECT_EQ(std::memcmp(got.data.data(), want.data.data(), want.data.size() * sizeof(float)),
                0)
          << isa_name(isa) << " channels " << channels;
    }
  }
}

}  // namespace
}  // namespace shadowlab
