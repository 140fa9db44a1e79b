// The 8-triangle setups (AVX-512 and AVX2) against setup_triangle, triangle by triangle: the
// same survivors in the same order, every field of every record bit for bit, the same counts.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/isa.h"
#include "raster/setup_simd.h"

namespace shadowlab {
namespace {

// Every triangle of 20,000 random batches through `fast` and through the scalar setup.
void expect_scalar_bits(SetupBatch8Fn fast) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), wdist(0.05f, 20.0f);
  size_t survived = 0, degenerate = 0, culled = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // Every 7th batch on a 2^20 × 2^20-pixel viewport: its corners reach 2^28 sub-pixel units,
    // where the area's products are no longer exact in double and the AVX2 form must hand the
    // batch to the scalar setup.
    const int width = trial % 7 == 0 ? 1 << 20 : trial % 3 == 0 ? 509 : 1024;
    const int height = trial % 7 == 0 ? 1 << 20 : trial % 5 == 0 ? 77 : 768;
    const CullMode cull = trial % 4 == 0 ? CullMode::Back : trial % 4 == 1 ? CullMode::Front
                                                                         : CullMode::None;
    SetupBatch8 b;
    b.count = 1 + trial % 8;
    // Triangles of every size: a centre in (or beyond) the viewport, corners from a scale of
    // 1e-4 pixel (sub-pixel, snapped to zero area) to beyond the viewport; some share a vertex.
    // On the wide viewport, corners up to a quarter of it apart: edge products past 2^53.
    const float scale =
        trial % 7 == 0 ? 0.5f : std::pow(10.0f, float(trial % 9) - 4.0f) / float(width);
    for (int k = 0; k < b.count; ++k) {
      const float cx = 1.5f * u(rng), cy = 1.5f * u(rng);
      for (int v = 0; v < 3; ++v) {
        const float w = wdist(rng);
        const bool repeat = v == 2 && (trial + k) % 11 == 0;  // a repeated vertex: zero area
        const float nx = repeat ? b.x[0][k] / b.w[0][k] : cx + scale * u(rng);
        const float ny = repeat ? b.y[0][k] / b.w[0][k] : cy + scale * u(rng);
        const float wv = repeat ? b.w[0][k] : w;
        b.x[v][k] = nx * wv;
        b.y[v][k] = ny * wv;
        b.w[v][k] = wv;
      }
      b.triangle[k] = uint32_t(trial * 8 + k);
    }
    TriangleSetup got[8], want[8];
    std::memset(got, 0, sizeof got);
    std::memset(want, 0, sizeof want);
    RasterStats sg, sw;
    const int ng = fast(b, width, height, cull, got, sg);
    const int nw = setup_batch8_scalar(b, width, height, cull, want, sw);
    ASSERT_EQ(ng, nw) << "trial " << trial;
    for (int i = 0; i < nw; ++i)
      ASSERT_EQ(0, std::memcmp(&got[i], &want[i], sizeof(TriangleSetup)))
          << "trial " << trial << " triangle " << want[i].triangle;
    ASSERT_EQ(sg.dropped_degenerate, sw.dropped_degenerate) << "trial " << trial;
    ASSERT_EQ(sg.culled_facing, sw.culled_facing) << "trial " << trial;
    survived += size_t(nw);
    degenerate += sw.dropped_degenerate;
    culled += sw.culled_facing;
  }
  ::testing::Test::RecordProperty("outcomes", std::to_string(survived) + " set up, " + std::to_string(degenerate) +
                                 " degenerate or empty, " + std::to_string(culled) + " culled");
  EXPECT_GT(survived, 10000u);
  EXPECT_GT(degenerate, 10000u);
  EXPECT_GT(culled, 5000u);
}

// Every vector table this CPU runs (the AVX2 form also where the AVX-512 one is in use).
TEST(SetupSimd, EveryTableGivesTheScalarSetupsBitForBit) {
  EXPECT_EQ(setup_kernels(Isa::scalar).batch8, nullptr);  // the front end's own scalar setup
  for (const Isa isa : cpu_isas()) {
    if (isa == Isa::scalar) continue;
    SCOPED_TRACE(isa_name(isa));
    ASSERT_EQ(setup_kernels(isa).isa, isa);
    expect_scalar_bits(setup_kernels(isa).batch8);
  }
}

}  // namespace
}  // namespace shadowlab
