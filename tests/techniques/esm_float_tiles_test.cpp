// ESM's float tiles (techniques/filters/esm/esm_float_tiles.h): which tiles they take, their values against
// long double within the header's analysed bound, and their vector kernels against their scalar
// ones bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/isa.h"
#include "techniques/filters/esm/esm_float_tiles.h"
#include "techniques/filters/esm/esm_tile_rows.h"
#include "techniques/filters/moments_common/moment_filter.h"
#include "techniques/pipeline/texel_tiles.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

float finite(float d) { return d < 1.0f ? d : 1.0f; }

// A w × h face: a smooth surface in [0.3, 0.6] with noise up to 1e-3 (so the window sums
// round), an empty texel (+inf: 1) in one tile (a range of ~0.7: the float path's largest
// exponents, ~70 at c = 200), a near texel (0.01) beside another empty one in a second tile (a
// range of 0.99: too wide for the float path at c = 200), exact ties.
std::vector<float> test_face(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(-1e-3f, 1e-3f);
  std::vector<float> d(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      d[size_t(y) * size_t(w) + size_t(x)] =
          0.45f + 0.15f * std::sin(0.05f * float(x)) * std::cos(0.07f * float(y)) + noise(rng);
  d[size_t(5) * size_t(w) + 40] = std::numeric_limits<float>::infinity();
  d[size_t(h - 3) * size_t(w) + 3] = 0.01f;
  d[size_t(h - 4) * size_t(w) + 5] = std::numeric_limits<float>::infinity();
  d[1] = d[2];
  return d;
}

// The smallest and largest finite distance tile (tx, ty)'s windows read.
void tile_range(const std::vector<float>& d, int w, int h, int k, int tx, int ty, float& lo,
                float& hi) {
  lo = 1.0f;
  hi = 0.0f;
  const int r = k / 2;
  for (int y = ty * 32 - r; y < std::min(h, ty * 32 + 32) + r; ++y)
    for (int x = tx * 32 - r; x < std::min(w, tx * 32 + 32) + r; ++x) {
      const float v = finite(d[size_t(std::clamp(y, 0, h - 1)) * size_t(w) +
                               size_t(std::clamp(x, 0, w - 1))]);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
}

// ln(mean over the k × k window of e^(c·d)) in long double (its range reaches e^11356).
double exact_value(const std::vector<float>& d, int w, int h, int k, double c, int x, int y) {
  long double s = 0.0L;
  for (int j = -k / 2; j <= k / 2; ++j)
    for (int i = -k / 2; i <= k / 2; ++i)
      s += std::exp((long double)c *
                    (long double)finite(d[size_t(std::clamp(y + j, 0, h - 1)) * size_t(w) +
                                          size_t(std::clamp(x + i, 0, w - 1))]));
  return double(std::log(s / (long double)(k * k)));
}

// The largest |c·(d − s)| over a tile whose distances span [lo, hi], s the float nearest the
// middle (the header's definition).
double largest_exponent(double c, float lo, float hi) {
  const double s = double(float((double(lo) + double(hi)) * 0.5));
  return c * std::max(double(hi) - s, s - double(lo));
}

double half_ulp(double v) {
  const float f = float(v);
  return 0.5 * double(std::nextafter(std::fabs(f), INFINITY) - std::fabs(f));
}

// The tiles the float path leaves are exactly those whose X = c·max(hi − s, s − lo) exceeds 80
// (s: the float nearest (lo + hi)/2), found
// here by a brute-force pass over each tile's windows; every texel of a taken tile is within
// the header's bound of the exact value: (X + 2k + 4)·2^-24 + 2e-7 + 3e-8 + half the stored
// float's ulp, X the tile's largest exponent (its exponents' rounding, relative
// |x|·2^-24 in each term; exp_f's 2 ulp; the k − 1 additions of each sum, the float 1/k² and the
// product; ln_m_f's 2e-7; the combine's small roundings; the store). The tiles left go through
// filter_esm_log's double path, checked by its own bound (moment_filter_test.cpp).
TEST(EsmFloatTiles, TakeTheTilesTheirRangeAllowsWithinTheAnalysedBound) {
  const double c = 200.0;
  double worst_ratio = 0.0, worst_error = 0.0;
  for (const auto& [w, h] : {std::pair{100, 70}, std::pair{64, 33}}) {
    const std::vector<float> d = test_face(w, h, unsigned(w));
    for (const int k : {1, 3, 5, 9}) {
      SCOPED_TRACE(k);
      std::vector<float> out(d.size(), 7.0f);
      FaceTiles rest;
      const size_t left = esm_float_tiles(d.data(), w, h, k, c, true, nullptr, out.data(), rest);
      const int tx_n = (w + 31) / 32, ty_n = (h + 31) / 32;
      ASSERT_EQ(rest.tiles_x, tx_n);
      ASSERT_EQ(rest.tiles_y, ty_n);
      size_t expect_left = 0;
      for (int ty = 0; ty < ty_n; ++ty)
        for (int tx = 0; tx < tx_n; ++tx) {
          float lo, hi;
          tile_range(d, w, h, k, tx, ty, lo, hi);
          const double x_max = largest_exponent(c, lo, hi);
          const bool taken = x_max <= 80.0;
          expect_left += taken ? 0 : 1;
          ASSERT_EQ(rest.need[size_t(ty * tx_n + tx)] == 0, taken) << tx << "," << ty;
          for (int y = ty * 32; y < std::min(h, ty * 32 + 32); ++y)
            for (int x = tx * 32; x < std::min(w, tx * 32 + 32); ++x) {
              const float got = out[size_t(y) * size_t(w) + size_t(x)];
              if (!taken) {
                ASSERT_EQ(got, 7.0f) << "a left tile's texel was written";
                continue;
              }
              const double truth = exact_value(d, w, h, k, c, x, y);
              const double bound =
                  (x_max + 2.0 * k + 4.0) * 0x1p-24 + 2e-7 + 3e-8 + half_ulp(truth);
              const double err = std::fabs(double(got) - truth);
              ASSERT_LE(err, bound) << x << "," << y;
              worst_ratio = test::worst_of(worst_ratio, err / bound);
              worst_error = test::worst_of(worst_error, err);
            }
        }
      EXPECT_EQ(left, expect_left);
      EXPECT_GE(expect_left, 1u);  // the tile with the near and empty texels
      EXPECT_LT(expect_left, size_t(tx_n * ty_n));  // and the float path takes the others
    }
  }
  std::printf("float tiles: worst error %.3g, %.2f of its bound\n", worst_error, worst_ratio);
}

// Every table this CPU has (techniques/filters/esm/esm_tile_rows.h) gives the scalar table's bits, on
// faces whose widths are no multiple of 32, 16 or 8 (the last tiles' columns go through the
// scalar rows), with and without tiles, for every width the float path takes, at c from 5 to
// 700 (at 700 most tiles are left).
void vector_kernels_give_the_scalar_bits() {
  for (const auto& [w, h] : {std::pair{100, 70}, std::pair{37, 41}, std::pair{1030, 35}}) {
    const std::vector<float> d = test_face(w, h, 7u);
    FaceTiles some;
    some.tiles_x = (w + 31) / 32;
    some.tiles_y = (h + 31) / 32;
    for (int i = 0; i < some.tiles_x * some.tiles_y; ++i) some.need.push_back(uint8_t(i % 3 != 1));
    for (const FaceTiles* tiles : {static_cast<const FaceTiles*>(nullptr), static_cast<const FaceTiles*>(&some)})
      for (const int k : {1, 3, 5, 7, 9})
        for (const double c : {5.0, 80.0, 200.0, 700.0}) {
          std::vector<float> fast(d.size(), 7.0f), slow(d.size(), 7.0f);
          FaceTiles rest_fast, rest_slow;
          const size_t a = esm_float_tiles(d.data(), w, h, k, c, true, tiles, fast.data(), rest_fast);
          const size_t b = esm_float_tiles(d.data(), w, h, k, c, false, tiles, slow.data(), rest_slow);
          ASSERT_EQ(a, b);
          ASSERT_EQ(rest_fast.need, rest_slow.need);
          ASSERT_EQ(std::memcmp(fast.data(), slow.data(), d.size() * 4), 0)
              << w << "x" << h << " k " << k << " c " << c << (tiles ? " tiles" : "");
        }
  }
}

TEST(EsmFloatTiles, VectorKernelsGiveTheScalarBits) {
  for (const Isa isa : cpu_isas()) {
    const ScopedIsa guard(isa);
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(esm_tile_kernels(process_isa()).isa, isa);
    vector_kernels_give_the_scalar_bits();
  }
}

// filter_esm_log with the float tiles and its double path: on a face where both run, every
// texel within its path's bound (above, and the double path's c·2^-24 + 5e-7 + half an ulp),
// and the same bits with tiles as without on the needed tiles.
TEST(EsmFloatTiles, FilterEsmLogJoinsBothPaths) {
  const int w = 100, h = 70, k = 3;
  const double c = 200.0;
  const std::vector<float> d = test_face(w, h, 100u);
  std::vector<float> out;
  filter_esm_log(d.data(), w, h, k, c, out);
  ASSERT_EQ(out.size(), d.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float lo, hi;
      tile_range(d, w, h, k, x / 32, y / 32, lo, hi);
      const double x_max = largest_exponent(c, lo, hi);
      const double truth = exact_value(d, w, h, k, c, x, y);
      const double bound = x_max <= 80.0
                               ? (x_max + 2.0 * k + 4.0) * 0x1p-24 + 2.3e-7 + half_ulp(truth)
                               : c * 0x1p-24 + 5e-7 + half_ulp(truth);
      ASSERT_NEAR(out[size_t(y) * size_t(w) + size_t(x)], truth, bound) << x << "," << y;
    }
}

}  // namespace
}  // namespace shadowlab
