// The SIMD depth kernels (AVX2, AVX-512) against their scalar oracle: identical bits on random
// blocks.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "raster/depth_kernels.h"

namespace shadowlab {
namespace {

void expect_matches_scalar(DepthBlock8Fn fast) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int64_t> edge(-(int64_t(1) << 40), int64_t(1) << 40);
  std::uniform_int_distribution<int64_t> step(-(int64_t(1) << 24), int64_t(1) << 24);
  std::uniform_real_distribution<float> zf(-2.0f, 2.0f);
  const size_t stride = 13;
  int inside_cases = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    DepthBlock8 b;
    for (int k = 0; k < 3; ++k) {
      // Small edge values on some trials so blocks are partially covered.
      b.edge[k] = trial % 3 ? edge(rng) >> (trial % 40) : edge(rng);
      b.step_x[k] = step(rng);
      b.step_y[k] = step(rng);
    }
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 8; ++i) b.lane_x[k][i] = b.step_x[k] * i;
    b.z0 = zf(rng) + 2.5f;
    b.z_dx = zf(rng) * 0.01f;
    b.z_dy = zf(rng) * 0.01f;
    b.z_lo = 0.5f + 0.1f * zf(rng);
    b.z_hi = b.z_lo + 3.0f;
    b.ox = int(rng() % 200);
    b.oy = int(rng() % 200);
    b.rows = 1 + int(rng() % 8);
    b.id = uint32_t(trial);
    float z_fast[8 * 13], z_slow[8 * 13];
    uint32_t id_fast[8 * 13], id_slow[8 * 13];
    for (size_t i = 0; i < 8 * stride; ++i) {
      z_fast[i] = z_slow[i] = (rng() & 1) ? 0.0f : 2.5f + zf(rng);
      id_fast[i] = id_slow[i] = 0xFFFFFFFFu;
    }
    DepthBlock8 bf = b, bs = b;
    // When every pixel of the block is covered (checked here by brute force), the fast path
    // may take its no-edge branch; it must still match the oracle.
    bool all_in = true;
    for (int r = 0; r < b.rows; ++r)
      for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k)
          all_in = all_in && b.edge[k] + b.step_x[k] * i + b.step_y[k] * r >= 0;
    bf.inside = all_in;
    inside_cases += all_in;
    bf.ids = id_fast;
    bs.ids = id_slow;
    fast(bf, z_fast, stride);
    depth_block8_scalar(bs, z_slow, stride);
    ASSERT_EQ(0, std::memcmp(z_fast, z_slow, sizeof z_fast)) << "trial " << trial;
    ASSERT_EQ(0, std::memcmp(id_fast, id_slow, sizeof id_fast)) << "trial " << trial;
  }
  EXPECT_GT(inside_cases, 100) << "the no-edge branch must be exercised";
}

TEST(DepthKernels, Avx2MatchesScalarOracleBitForBit) {
  const DepthBlock8Fn fast = depth_block8_avx2();
  if (!fast) GTEST_SKIP() << "no AVX2 on this CPU: only the scalar path exists";
  expect_matches_scalar(fast);
}

TEST(DepthKernels, Avx512MatchesScalarOracleBitForBit) {
  const DepthBlock8Fn fast = depth_block8_avx512();
  if (!fast) GTEST_SKIP() << "no AVX-512 on this CPU";
  expect_matches_scalar(fast);
}

}  // namespace
}  // namespace shadowlab
