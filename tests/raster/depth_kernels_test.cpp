// The row kernels (scalar oracle, AVX2) against a brute-force loop over the pixels: identical
// bits on random rows of blocks. The AVX-512 path walks whole triangles; the frame-level tests
// (tests/raster/reference_rasterizer_test.cpp) compare it with the general path.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>
#include <algorithm>

#include "raster/depth_kernels.h"

namespace shadowlab {
namespace {

// A row kernel against a brute-force loop over the row's pixels (each pixel's exact edge
// values from the row's origin, the plane, the depth test): the blocks' skip and whole-coverage
// tests must change nothing. Edge values and steps are sized so that rows are partly covered,
// blocks skipped, and blocks wholly covered.
void expect_row_matches_brute_force(DepthRow8Fn fn) {
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<int64_t> edge(-(int64_t(1) << 21), int64_t(1) << 21);
  std::uniform_int_distribution<int64_t> step(-(int64_t(1) << 16), int64_t(1) << 16);
  std::uniform_real_distribution<float> zf(-2.0f, 2.0f);
  constexpr int kMaxBlocks = 9;
  const size_t stride = 8 * kMaxBlocks + 5;
  int skipped = 0, whole = 0, partial = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    DepthRow8 r;
    r.rows = 1 + int(rng() % 8);
    r.blocks = int(rng() % (kMaxBlocks + 1));
    for (int k = 0; k < 3; ++k) {
      r.edge[k] = edge(rng) + (trial % 4 == 0 ? (int64_t(1) << 22) : 0);  // some rows all inside
      r.step_x[k] = step(rng) >> (trial % 5);
      r.step_y[k] = step(rng) >> (trial % 7);
      if (trial % 9 == 8) {  // a large triangle's magnitudes: edges near 2^40, steps near 2^24
        r.edge[k] <<= 18;
        r.step_x[k] <<= 8;
        r.step_y[k] <<= 8;
      }
      r.block_step[k] = r.step_x[k] * 8;
      const int64_t x_span = r.step_x[k] * 7, dy = r.step_y[k] * (r.rows - 1);
      r.lo_off[k] = std::min<int64_t>(0, x_span) + std::min<int64_t>(0, dy);
      r.hi_off[k] = std::max<int64_t>(0, x_span) + std::max<int64_t>(0, dy);
    }
    r.z0 = zf(rng) + 2.5f;
    r.z_dx = zf(rng) * 0.01f;
    r.z_dy = zf(rng) * 0.01f;
    r.z_lo = 0.5f + 0.1f * zf(rng);
    r.z_hi = r.z_lo + 3.0f;
    r.ox = int(rng() % 200);
    r.oy = int(rng() % 200);
    r.id = uint32_t(trial);
    std::vector<float> z_got(8 * stride), z_want(8 * stride);
    std::vector<uint32_t> id_got(8 * stride, 0xFFFFFFFFu), id_want(8 * stride, 0xFFFFFFFFu);
    for (size_t i = 0; i < z_got.size(); ++i) z_got[i] = z_want[i] = (rng() & 1) ? 0.0f : 2.5f + zf(rng);
    for (int j = 0; j < r.blocks; ++j) {
      int covered = 0;
      for (int row = 0; row < r.rows; ++row)
        for (int i = 0; i < 8; ++i) {
          bool in = true;
          for (int k = 0; k < 3; ++k)
            in = in && r.edge[k] + r.block_step[k] * j + r.step_x[k] * i + r.step_y[k] * row >= 0;
          if (!in) continue;
          ++covered;
          const float zy = r.z0 + r.z_dy * float(r.oy + row);
          const float iw = std::min(std::max(zy + r.z_dx * float(r.ox + 8 * j + i), r.z_lo), r.z_hi);
          const size_t at = size_t(row) * stride + 8 * size_t(j) + size_t(i);
          if (iw > z_want[at]) {
            z_want[at] = iw;
            id_want[at] = r.id;
          }
        }
      skipped += covered == 0;
      whole += covered == 8 * r.rows;
      partial += covered > 0 && covered < 8 * r.rows;
    }
    r.ids = id_got.data();
    fn(r, z_got.data(), stride);
    ASSERT_EQ(0, std::memcmp(z_got.data(), z_want.data(), z_got.size() * sizeof(float))) << "trial " << trial;
    ASSERT_EQ(id_got, id_want) << "trial " << trial;
  }
  testing::Test::RecordProperty("blocks", std::to_string(skipped) + " empty, " + std::to_string(whole) +
                               " whole, " + std::to_string(partial) + " partial");
  EXPECT_GT(skipped, 1000);
  EXPECT_GT(whole, 1000);
  EXPECT_GT(partial, 1000);
}

TEST(DepthKernels, ScalarRowMatchesBruteForce) { expect_row_matches_brute_force(depth_row8_scalar); }

// Every table's row this CPU runs (the AVX-512 table's is the AVX2 row).
TEST(DepthKernels, EveryTablesRowMatchesBruteForce) {
  for (const Isa isa : cpu_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(depth_kernels(isa).isa, isa);
    expect_row_matches_brute_force(depth_kernels(isa).row8);
  }
}

}  // namespace
}  // namespace shadowlab
