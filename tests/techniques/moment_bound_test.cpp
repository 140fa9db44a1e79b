// The moment shadow map's reconstruction (techniques/filters/msm/moment_bound.h) against independent
// computations: the Hankel solve against long-double Gaussian elimination; distributions whose
// bound is known in closed form (two Dirac deltas, whose moments determine them; three atoms at
// 0, u and 1 for the Hausdorff bound); the lower-bound property on random distributions; the
// 16-bit quantization's matrices; the vector lanes (techniques/lookup/lookup_batches.h) against the
// scalar bits.
#include "techniques/filters/msm/moment_bound.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/isa.h"
#include "techniques/lookup/lookup_batches.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

struct Atom {
  double x, w;
};

void moments_of(const std::vector<Atom>& atoms, double m[4]) {
  for (int k = 0; k < 4; ++k) {
    long double s = 0.0L;
    for (const Atom& a : atoms) s += (long double)a.w * std::pow((long double)a.x, k + 1);
    m[k] = double(s);
  }
}

double fraction_before(const std::vector<Atom>& atoms, double z) {
  double s = 0.0;
  for (const Atom& a : atoms) s += a.x < z ? a.w : 0.0;
  return s;
}

std::vector<Atom> random_atoms(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Atom> atoms;
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    atoms.push_back({u(rng), 0.05 + u(rng)});
    total += atoms.back().w;
  }
  for (Atom& a : atoms) a.w /= total;
  return atoms;
}

// B·c = (1, z, z²) by Gaussian elimination with partial pivoting in long double.
void long_double_solve(const double b[4], double z, long double c[3]) {
  long double A[3][4] = {{1.0L, b[0], b[1], 1.0L},
                         {b[0], b[1], b[2], (long double)z},
                         {b[1], b[2], b[3], (long double)z * z}};
  for (int col = 0; col < 3; ++col) {
    int piv = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::fabs(A[r][col]) > std::fabs(A[piv][col])) piv = r;
    for (int k = 0; k < 4; ++k) std::swap(A[col][k], A[piv][k]);
    for (int r = col + 1; r < 3; ++r) {
      const long double f = A[r][col] / A[col][col];
      for (int k = col; k < 4; ++k) A[r][k] -= f * A[col][k];
    }
  }
  for (int r = 2; r >= 0; --r) {
    long double s = A[r][3];
    for (int k = r + 1; k < 3; ++k) s -= A[r][k] * c[k];
    c[r] = s / A[r][r];
  }
}

// The LDLᵀ solve in double against long-double elimination, on the biased moments of random
// 5-atom distributions: measured worst relative error 1.4e-10 over 2000 (bound 5e-10; atoms
// close together make B nearly singular, condition numbers up to ~1e6).
TEST(MomentBound, HankelSolveMatchesLongDoubleElimination) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::vector<Atom> atoms = random_atoms(rng, 5);
    double m[4], b[4];
    moments_of(atoms, m);
    msm_bias(m, 3e-6, b);
    const double z = u(rng);
    const HankelSolution c = hankel_solve(b, z);
    long double ref[3];
    long_double_solve(b, z, ref);
    // The solve returns k·c (k = d22·d33 > 0); divided out here in long double.
    ASSERT_GT(c.k, 0.0) << trial;
    const long double got[3] = {c.c1 / (long double)c.k, c.c2 / (long double)c.k,
                                c.c3 / (long double)c.k};
    const long double scale = std::max({std::fabs(ref[0]), std::fabs(ref[1]), std::fabs(ref[2])});
    for (int i = 0; i < 3; ++i) worst = test::worst_of(worst, double(std::fabs(got[i] - ref[i]) / scale));
  }
  RecordProperty("worst_relative_error", fmt::format("{:.3g}", worst));
  EXPECT_LT(worst, 5e-10);
}

// Two Dirac deltas (weights wa at za, 1 − wa at zb): the moments determine the distribution,
// so the sharpest lower bound on P(x < z) is that distribution's own: 0 before za, wa between,
// 1 beyond zb. The bias α moves it by O(α): measured worst 2.3e-5 at α = 1e-10 and 2.3e-7 at
// 1e-12 (the closest pair, 0.2 and 0.25, has the largest constant); bounds 1e-4 and 1e-6 with
// the 100-fold fall between them required. Both variants: the roots lie in [0, 1].
TEST(MomentBound, TwoDiracDeltasGiveTheirOwnFraction) {
  struct Case {
    double za, zb, wa;
  };
  double worst[2] = {0.0, 0.0};
  for (const Case& cs : {Case{0.3, 0.7, 0.4}, Case{0.1, 0.9, 0.75}, Case{0.45, 0.55, 0.5},
                         Case{0.2, 0.25, 0.1}}) {
    const std::vector<Atom> atoms = {{cs.za, cs.wa}, {cs.zb, 1.0 - cs.wa}};
    double m[4];
    moments_of(atoms, m);
    for (const double z : {cs.za - 0.05, 0.5 * (cs.za + cs.zb), cs.zb + 0.05}) {
      const double want = fraction_before(atoms, z);
      for (const bool hausdorff : {false, true})
        for (int i = 0; i < 2; ++i) {
          const double g = msm_intensity(m, z, i == 0 ? 1e-10 : 1e-12, hausdorff);
          worst[i] = test::worst_of(worst[i], std::fabs(g - want));
        }
    }
  }
  RecordProperty("worst_error_1e-10", fmt::format("{:.3g}", worst[0]));
  RecordProperty("worst_error_1e-12", fmt::format("{:.3g}", worst[1]));
  EXPECT_LT(worst[0], 1e-4);
  EXPECT_LT(worst[1], 1e-6);
  EXPECT_LT(worst[1], worst[0] / 50.0);
}

// Atoms at 0, u and 1: on [0, 1] this is the representation with atoms 0, z, u, 1 whose weight
// at z is 0, so the Hausdorff bound is exactly w0 + (u < z ? w_u : 0); the Hamburger bound,
// free to place atoms outside [0, 1], is lower (and on some z far lower: the branch matters).
TEST(MomentBound, HausdorffBoundOfAtomsAtTheEndsIsExact) {
  double hamburger_gap = 0.0;
  for (const double u : {0.3, 0.6}) {
    const std::vector<Atom> atoms = {{0.0, 0.3}, {u, 0.3}, {1.0, 0.4}};
    double m[4];
    moments_of(atoms, m);
    for (double z = 0.05; z < 1.0; z += 0.1) {
      const double want = fraction_before(atoms, z);
      const double haus = msm_intensity(m, z, 0.0, true);
      const double ham = msm_intensity(m, z, 0.0, false);
      EXPECT_NEAR(haus, want, 1e-9) << "u " << u << " z " << z;
      EXPECT_LE(ham, haus + 1e-12) << "u " << u << " z " << z;
      hamburger_gap = test::worst_of(hamburger_gap, haus - ham);
    }
  }
  EXPECT_GT(hamburger_gap, 0.05);
}

// A lower bound: on random distributions on [0, 1], Hamburger <= Hausdorff <= the true fraction
// in front (α = 0; 1e-9 for rounding).
TEST(MomentBound, BothVariantsBoundTheTrueFractionFromBelow) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int strict = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::vector<Atom> atoms = random_atoms(rng, 3 + trial % 4);
    double m[4];
    moments_of(atoms, m);
    const double z = u(rng);
    const double truth = fraction_before(atoms, z);
    const double ham = msm_intensity(m, z, 0.0, false);
    const double haus = msm_intensity(m, z, 0.0, true);
    ASSERT_LE(ham, haus + 1e-9) << trial;
    ASSERT_LE(haus, truth + 1e-9) << trial;
    strict += haus > ham + 1e-6;
  }
  EXPECT_GT(strict, 100);  // the Hausdorff branch is taken and tighter on many
}

// α = 0 over a footprint of one depth (a singular Hankel matrix): the solve divides by zero and
// the pixel counts as lit even behind the occluder (the leak the bias exists to prevent); the
// default α shadows it.
TEST(MomentBound, ZeroBiasLeaksOnASingleDepth) {
  const double d = 0.4;
  const double m[4] = {d, d * d, d * d * d, d * d * d * d};
  EXPECT_EQ(msm_intensity(m, 0.6, 0.0, false), 0.0);
  EXPECT_GT(msm_intensity(m, 0.6, 3e-6, false), 0.99);
  EXPECT_EQ(msm_intensity(m, 0.2, 3e-6, false), 0.0);
}

// The published 16-bit matrices are each other's inverse (to their 10 printed digits), and the
// moments of every depth in [0, 1] encode into [0, 1]⁴ (a UNORM16 store loses nothing to
// clamping). Measured: worst |Θ·Θ⁻¹ − I| 3.1e-9; encoded range [0.0120, 0.9900].
TEST(MomentBound, SixteenBitQuantizationMatricesAreInversesAndFitUnorm) {
  double worst = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      long double s = 0.0L;
      for (int k = 0; k < 4; ++k) s += (long double)kMsmTheta[i][k] * kMsmInverse[k][j];
      worst = test::worst_of(worst, double(std::fabs(s - (i == j ? 1.0L : 0.0L))));
    }
  EXPECT_LT(worst, 1e-8);
  double lo = 1.0, hi = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double d = i / 1000.0;
    const double m[4] = {d, d * d, d * d * d, d * d * d * d};
    double q[4], back[4];
    msm_encode16(m, q);
    for (double v : q) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    msm_decode16(q, back);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(back[k], m[k], 1e-7) << d;
  }
  RecordProperty("encoded_range", std::to_string(lo) + " " + std::to_string(hi));
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
}

// A `lanes`-wide form against the scalar bits: random distributions, α = 0 (singular and NaN
// lanes included: one-depth footprints) and the default, both variants.
template <class Kernel>
void expect_scalar_bits(int lanes, const Kernel& kernel) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    double m[4][32], z[32];
    for (int lane = 0; lane < lanes; ++lane) {
      const int n = (trial + lane) % 5 + 1;  // 1 atom: a singular matrix
      double mm[4];
      moments_of(random_atoms(rng, n), mm);
      for (int k = 0; k < 4; ++k) m[k][lane] = mm[k];
      z[lane] = u(rng);
    }
    for (const double alpha : {0.0, 3e-6, 1e-2})
      for (const bool hausdorff : {false, true}) {
        double got[32];
        kernel(m, z, alpha, hausdorff, got);
        for (int lane = 0; lane < lanes; ++lane) {
          const double mm[4] = {m[0][lane], m[1][lane], m[2][lane], m[3][lane]};
          const double want = msm_intensity(mm, z[lane], alpha, hausdorff);
          ASSERT_EQ(std::memcmp(&got[lane], &want, 8), 0)
              << trial << " lane " << lane << " " << got[lane] << " vs " << want;
          ++compared;
        }
      }
  }
  EXPECT_EQ(compared, 4000 * lanes * 6);
}

// Every table this CPU has (techniques/lookup/lookup_batches.h): its reconstruction on one group of
// lanes and on the groups the MSM lookup runs side by side (AVX2: 2 × 4, AVX-512: 4 × 8).
TEST(MomentBound, EveryTablesLanesGiveTheScalarBits) {
  int tables = 0;
  for (const Isa isa : cpu_isas()) {
    const LookupBatchKernels& k = lookup_batch_kernels(isa);
    if (isa == Isa::scalar) {
      EXPECT_EQ(k.msm_intensity, nullptr);
      continue;
    }
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(k.isa, isa);
    ASSERT_LE(k.msm_lanes_groups, 32);
    expect_scalar_bits(k.msm_lanes, k.msm_intensity);
    expect_scalar_bits(k.msm_lanes_groups, k.msm_intensity_groups);
    ++tables;
  }
  EXPECT_EQ(tables, int(cpu_isas().size()) - 1);
}

}  // namespace
}  // namespace shadowlab
