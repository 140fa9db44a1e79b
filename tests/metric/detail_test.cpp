#include "metric/detail.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace shadowlab {
namespace {

// Texel index of square blocks of side b (every pixel of a block shares one texel). `scramble`
// spreads the indices over all 32 bits.
ImageU32 blocks(int w, int h, int b, uint32_t scramble = 1) {
  ImageU32 t(w, h, 1);
  const int bw = (w + b - 1) / b;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.at(x, y) = uint32_t((y / b) * bw + x / b) * scramble;
  return t;
}

TEST(Detail, BlockSizesGiveInverseSquaredSide) {
  // Every pixel shares its texel with b² pixels: S_ratio = b², detail = 1/b².
  EXPECT_DOUBLE_EQ(texel_share_ratio(blocks(8, 6, 2)), 4.0);
  ImageU32 two = blocks(8, 6, 2);
  EXPECT_DOUBLE_EQ(detail_score(&two), 0.25);
  ImageU32 one = blocks(8, 6, 1);
  EXPECT_DOUBLE_EQ(detail_score(&one), 1.0);
  ImageU32 three = blocks(9, 6, 3);
  EXPECT_DOUBLE_EQ(detail_score(&three), 1.0 / 9.0);
  ImageU32 scrambled = blocks(12, 9, 3, 0x9E3779B1u);  // odd multiplier: still distinct indices
  EXPECT_DOUBLE_EQ(detail_score(&scrambled), 1.0 / 9.0);
}

TEST(Detail, UnevenSharingAndPixelsWithoutTexel) {
  // Texel 7 on three pixels, texel 2 on one, the rest kNoTexel: per-pixel counts 3, 3, 3, 1,
  // mean square (27 + 1)/4 = 7 → S_ratio = √7.
  ImageU32 t(5, 3, 1, kNoTexel);
  t.at(0, 0) = 7;
  t.at(4, 2) = 7;
  t.at(2, 1) = 7;
  t.at(1, 1) = 2;
  EXPECT_DOUBLE_EQ(detail_score(&t), 1.0 / std::sqrt(7.0));
}

TEST(Detail, IndicesEqualInTheirLow22BitsStayDistinct) {
  // csm:res=1024 indices reach 6·1024² > 2^22, so texels of different faces can share their low
  // 22 (or 11, or 21) bits. Three indices that differ only above bit 22, interleaved so that a
  // sort on the low bits alone would leave equal keys apart: A on 3 pixels, B on 2, C on 1.
  // Per-pixel counts 3,3,3,2,2,1: S_ratio = √((27 + 8 + 1)/6) = √6.
  const uint32_t low = 0x2A5A5Au;  // some 22-bit pattern
  const uint32_t A = low, B = low | (1u << 22), C = low | (5u << 22);
  ImageU32 t(6, 1, 1);
  const uint32_t order[6] = {A, B, A, C, B, A};
  for (int x = 0; x < 6; ++x) t.at(x, 0) = order[x];
  EXPECT_DOUBLE_EQ(texel_share_ratio(t), std::sqrt(6.0));
  // Real csm:res=1024 indices: face 5's texel (x, y) and face 1's, 4·1024² apart.
  const uint32_t face_texels = 1024u * 1024u;
  ImageU32 u(4, 1, 1);
  u.at(0, 0) = 5 * face_texels + 77;
  u.at(1, 0) = 1 * face_texels + 77;
  u.at(2, 0) = 5 * face_texels + 77;
  u.at(3, 0) = 1 * face_texels + 77;
  EXPECT_DOUBLE_EQ(texel_share_ratio(u), 2.0);  // two texels of two pixels each
}

TEST(Detail, NoTexelImageOrNoTexelPixelScoresOne) {
  EXPECT_EQ(detail_score(nullptr), 1.0);
  ImageU32 none(4, 4, 1, kNoTexel);
  EXPECT_EQ(detail_score(&none), 1.0);
}

TEST(Detail, MatchesMapCountOnRandomIndices) {
  // Oracle: counts from std::map, then the RMS of the per-pixel counts.
  std::mt19937 rng(99);
  for (int trial = 0; trial < 20; ++trial) {
    ImageU32 t(37, 23, 1);
    const uint32_t range = 1 + rng() % 300;
    for (uint32_t& v : t.data) {
      const uint32_t r = rng();
      v = r % 5 == 0 ? kNoTexel : (r % range) * 0x01000193u + (trial % 2 ? 0xFF000000u : 0u);
    }
    std::map<uint32_t, double> count;
    for (const uint32_t v : t.data)
      if (v != kNoTexel) count[v] += 1.0;
    double sum = 0.0, n = 0.0;
    for (const uint32_t v : t.data)
      if (v != kNoTexel) {
        sum += count[v] * count[v];
        n += 1.0;
      }
    EXPECT_NEAR(texel_share_ratio(t), std::sqrt(sum / n), 1e-12) << "trial " << trial;
  }
}

}  // namespace
}  // namespace shadowlab
