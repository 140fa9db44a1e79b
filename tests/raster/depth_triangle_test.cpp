// The depth-only paths against the general per-fragment path (rasterize_triangle_in_rect,
// which tests every pixel of a block on its own): the one in use on this machine
// (rasterize_depth_in_rect: the AVX-512 whole-triangle walk, the AVX2 rows of blocks or the
// scalar oracle's), and the AVX-512 walk on its own where the CPU has it. Random
// triangles set up by setup_triangle, drawn over random depths tile by tile, must leave the
// same bytes of depth and ids. Viewports whose width is not a multiple of 8 cut the last block
// of a row (the AVX-512 walk masks its lanes); triangles reach into the guard band, where edge
// values pass int32 within a block. (An AVX2 form of this walk was measured and not kept:
// docs/performance_history.md; it passed this test, which failed with its
// int32 range check or its cut block broken.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "raster/depth_kernels.h"
#include "raster/rasterize_tile.h"
#include "raster/setup.h"

namespace shadowlab {
namespace {

// Keeps every fragment without declaring kKeepsAll: rasterize_triangle_in_rect's general path.
struct KeepAll {
  static constexpr bool kNeedsAttributes = false;
  bool operator()(const Fragment&) const { return true; }
};

// True when some edge of s can exceed int32 inside one 8 × 8 block that it crosses: its span
// over the block, 7 · (|step_x| + |step_y|), at least 2^31.
bool wide_edges(const TriangleSetup& s) {
  for (int k = 0; k < 3; ++k) {
    const int64_t span = 7 * (std::abs(s.a[k]) + std::abs(s.b[k])) * kSubpixelOne;
    if (span >= (int64_t(1) << 31)) return true;
  }
  return false;
}

// `draw(s, x0, y0, x1, y1, target)`: the depth-only path under test, one tile of triangle s.
template <class Draw>
void expect_walk_matches_general_path(const Draw& draw) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), wdist(0.2f, 5.0f), zinit(0.0f, 1.5f);
  int drawn = 0, wide = 0, cut_tiles = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Widths that cut the last block (not multiples of 8) and ones that do not.
    const int width = trial % 3 == 0 ? 203 : trial % 3 == 1 ? 256 : 131;
    const int height = trial % 2 == 0 ? 150 : 64;
    const bool with_ids = trial % 2 == 1;
    DepthTarget got, want;
    for (DepthTarget* t : {&got, &want}) {
      t->width = width;
      t->height = height;
      t->with_ids = with_ids;
    }
    got.inv_w.resize(size_t(width) * size_t(height));
    for (float& z : got.inv_w) z = (rng() % 3 == 0) ? 0.0f : zinit(rng);
    want.inv_w = got.inv_w;
    if (with_ids) got.ids = want.ids = std::vector<uint32_t>(got.inv_w.size(), 0xFFFFFFFFu);
    // Triangles from a few pixels to far beyond the viewport (every 4th: corners up to 40
    // viewports out, the guard band's magnitudes).
    for (int t = 0; t < 24; ++t) {
      const float reach = (t % 4 == 3) ? 40.0f : std::pow(10.0f, float(t % 3) - 2.0f) * 1.5f;
      const float cx = 1.2f * u(rng), cy = 1.2f * u(rng);
      ClipVertex v[3];
      for (ClipVertex& cv : v) {
        const float w = wdist(rng);
        cv.clip = vec4((cx + reach * u(rng)) * w, (cy + reach * u(rng)) * w, 0.5f * u(rng) * w, w);
        cv.bary = vec3(0.0f);
      }
      TriangleSetup s;
      RasterStats stats;
      if (!setup_triangle(v[0], v[1], v[2], uint32_t(trial * 100 + t), width, height,
                          CullMode::None, s, stats))
        continue;
      ++drawn;
      wide += wide_edges(s);
      KeepAll keep;
      for (int y0 = 0; y0 < height; y0 += kTileSize)
        for (int x0 = 0; x0 < width; x0 += kTileSize) {
          const int x1 = std::min(width, x0 + kTileSize), y1 = std::min(height, y0 + kTileSize);
          cut_tiles += t == 0 && (x1 - x0) % 8 != 0;
          draw(s, x0, y0, x1, y1, got);
          rasterize_triangle_in_rect(s, x0, y0, x1, y1, want, keep);
        }
    }
    ASSERT_EQ(0, std::memcmp(got.inv_w.data(), want.inv_w.data(), got.inv_w.size() * sizeof(float)))
        << "trial " << trial;
    ASSERT_EQ(got.ids, want.ids) << "trial " << trial;
  }
  testing::Test::RecordProperty("triangles", std::to_string(drawn) + " drawn, " +
                                                 std::to_string(wide) + " with wide edges");
  EXPECT_GT(drawn, 5000);
  EXPECT_GT(wide, 500);
  EXPECT_GT(cut_tiles, 100);
}

TEST(DepthTriangle, DepthOnlyPathInUseMatchesTheGeneralPath) {
  expect_walk_matches_general_path(
      [](const TriangleSetup& s, int x0, int y0, int x1, int y1, DepthTarget& t) {
        rasterize_depth_in_rect(s, x0, y0, x1, y1, t);
      });
}

TEST(DepthTriangle, Avx512WalkMatchesTheGeneralPath) {
  EXPECT_EQ(depth_kernels(Isa::scalar).triangle, nullptr);
  EXPECT_EQ(depth_kernels(Isa::avx2).triangle, nullptr);
  if (cpu_isa() != Isa::avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  const DepthTriangleFn walk = depth_kernels(Isa::avx512).triangle;
  ASSERT_NE(walk, nullptr);
  expect_walk_matches_general_path(
      [walk](const TriangleSetup& s, int x0, int y0, int x1, int y1, DepthTarget& t) {
        walk(s, x0, y0, x1, y1, t.inv_w.data(), t.with_ids ? t.ids.data() : nullptr,
             size_t(t.width));
      });
}

}  // namespace
}  // namespace shadowlab
