// GBuffer block bounds (core/block_bounds.h): the AVX2 path for fully covered segments and the
// pixel-by-pixel path both give the brute-force bounds; NaN and infinite positions; every table
// of BlockBoundsKernels gives the scalar table's bytes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

#include "core/block_bounds.h"
#include "core/isa.h"

namespace shadowlab {
namespace {

// Brute force: min and max of the covered positions of each block (lo > hi when none).
std::vector<BlockBounds> brute_force(const GBuffer& g) {
  std::vector<BlockBounds> out(size_t(g.blocks_x()) * size_t(g.blocks_y()));
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x);
      if (!g.covered[i]) continue;
      BlockBounds& b = out[size_t(y / 16) * size_t(g.blocks_x()) + size_t(x / 16)];
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(b.lo[k], g.position[i][k]);
        b.hi[k] = std::max(b.hi[k], g.position[i][k]);
      }
    }
  return out;
}

// A 100 × 40 GBuffer (the last block column and row partial) with random positions; each block
// fully covered, empty, or covered at random.
GBuffer random_gbuffer(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  GBuffer g;
  g.resize(100, 40);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x);
      const int kind = ((x / 16) * 7 + (y / 16) * 3) % 3;  // 0 full, 1 empty, 2 random
      g.covered[i] = kind == 0 ? 1 : kind == 1 ? 0 : uint8_t(rng() & 1u);
      g.position[i] = vec3(u(rng), u(rng), u(rng));
    }
  return g;
}


TEST(BlockBounds, BothPathsGiveTheBruteForceBounds) {
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    GBuffer g = random_gbuffer(seed);
    const std::vector<BlockBounds> expected = brute_force(g);
    for (bool scalar : {false, true}) {
      const ScopedIsa paths(scalar ? Isa::scalar : cpu_isa());
      g.block_bounds.clear();
      compute_block_bounds(g);
      ASSERT_TRUE(g.has_block_bounds());
      for (size_t b = 0; b < expected.size(); ++b) {
        ASSERT_EQ(g.block_bounds[b].empty(), expected[b].empty()) << b;
        if (expected[b].empty()) continue;
        EXPECT_EQ(g.block_bounds[b].lo, expected[b].lo) << "block " << b << " scalar " << scalar;
        EXPECT_EQ(g.block_bounds[b].hi, expected[b].hi) << "block " << b << " scalar " << scalar;
      }
    }
  }
}

// A NaN position makes its block ±inf (whether the block is fully covered, so on the AVX2 path,
// or partially); an infinite one reaches the bounds.
TEST(BlockBounds, NonFinitePositions) {
  const float inf = std::numeric_limits<float>::infinity();
  for (bool scalar : {false, true}) {
    const ScopedIsa paths(scalar ? Isa::scalar : cpu_isa());
    GBuffer g = random_gbuffer(9);
    // Block (0, 0) is fully covered (kind 0), block (2, 0) covered at random (kind 14 mod 3),
    // block (0, 1) fully covered (kind 3 mod 3).
    g.position[size_t(5 * 100 + 7)].y = std::numeric_limits<float>::quiet_NaN();
    size_t partial = 0;
    for (int x = 32; x < 48; ++x)
      if (g.covered[size_t(3 * 100 + x)]) partial = size_t(3 * 100 + x);
    ASSERT_NE(partial, 0u);
    g.position[partial].z = std::numeric_limits<float>::quiet_NaN();
    g.position[size_t(20 * 100 + 3)].x = inf;  // block (0, 1): full
    compute_block_bounds(g);
    for (size_t b : {size_t(0), size_t(2)}) {
      EXPECT_EQ(g.block_bounds[b].lo, vec3(-inf)) << b << " scalar " << scalar;
      EXPECT_EQ(g.block_bounds[b].hi, vec3(inf)) << b << " scalar " << scalar;
    }
    const BlockBounds& b01 = g.block_bounds[size_t(g.blocks_x())];
    EXPECT_EQ(b01.hi.x, inf);
    EXPECT_LT(b01.lo.x, 0.0f);
    EXPECT_TRUE(std::isfinite(b01.hi.y));
  }
}

// Every table this CPU runs, through the camera pass's BlockRowBounds, against the scalar table
// byte for byte (bounds, NaN blocks and all) on the random GBuffers with a NaN in a fully
// covered segment.
TEST(BlockBounds, EveryTableGivesTheScalarBytes) {
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    GBuffer want = random_gbuffer(seed);
    want.position[size_t(2 * 100 + 5)].x = std::numeric_limits<float>::quiet_NaN();  // block 0
    GBuffer got = want;
    {
      const ScopedIsa scalar(Isa::scalar);
      compute_block_bounds(want);
    }
    for (const Isa isa : cpu_isas()) {
      const ScopedIsa scoped(isa);
      got.block_bounds.clear();
      compute_block_bounds(got);
      ASSERT_EQ(got.block_bounds.size(), want.block_bounds.size());
      EXPECT_EQ(std::memcmp(got.block_bounds.data(), want.block_bounds.data(),
                            want.block_bounds.size() * sizeof(BlockBounds)),
                0)
          << isa_name(isa) << " seed " << seed;
    }
  }
}

}  // namespace
}  // namespace shadowlab
