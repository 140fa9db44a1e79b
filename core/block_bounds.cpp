#include "core/block_bounds.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/isa.h"
#include "core/simd_target.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace shadowlab {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Component of lane k of the segment's vector j (and j + 3): (8j + k) mod 3.
int lane_component(int j, int k) { return (8 * j + k) % 3; }

#if defined(__x86_64__)
// A fully covered 16-pixel segment (48 floats at f) into the block's six vectors; returns true
// when a float is NaN.
SL_TARGET("avx2") bool add_full_segment_avx2(const float* f, float* lanes) {
  __m256 lo[3], hi[3];
  __m256 nan = _mm256_setzero_ps();
  for (int j = 0; j < 3; ++j) {
    lo[j] = _mm256_loadu_ps(lanes + 8 * j);
    hi[j] = _mm256_loadu_ps(lanes + 24 + 8 * j);
  }
  for (int v = 0; v < 6; ++v) {
    const __m256 p = _mm256_loadu_ps(f + 8 * v);
    const int j = v % 3;
    nan = _mm256_or_ps(nan, _mm256_cmp_ps(p, p, _CMP_UNORD_Q));
    lo[j] = _mm256_min_ps(p, lo[j]);  // p < lo ? p : lo (the scalar path's form)
    hi[j] = _mm256_max_ps(p, hi[j]);  // p > hi ? p : hi
  }
  for (int j = 0; j < 3; ++j) {
    _mm256_storeu_ps(lanes + 8 * j, lo[j]);
    _mm256_storeu_ps(lanes + 24 + 8 * j, hi[j]);
  }
  return _mm256_movemask_ps(nan) != 0;
}

// Minimum (or maximum) over the lanes of v whose component is c, with the other lanes set to
// `fill` (+inf for a minimum, −inf for a maximum).
template <bool kMax>
SL_TARGET("avx2") float fold_component(const float* v, int c, float fill) {
  __m256 m = _mm256_set1_ps(fill);
  for (int j = 0; j < 3; ++j) {
    alignas(32) int32_t sel[8];
    for (int k = 0; k < 8; ++k) sel[k] = lane_component(j, k) == c ? -1 : 0;
    const __m256 x = _mm256_blendv_ps(_mm256_set1_ps(fill), _mm256_loadu_ps(v + 8 * j),
                                      _mm256_castsi256_ps(_mm256_load_si256(
                                          reinterpret_cast<const __m256i*>(sel))));
    m = kMax ? _mm256_max_ps(x, m) : _mm256_min_ps(x, m);
  }
  __m256 s = _mm256_permute2f128_ps(m, m, 1);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  s = _mm256_shuffle_ps(m, m, 0x4E);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  s = _mm256_shuffle_ps(m, m, 0xB1);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  return _mm256_cvtss_f32(m);
}
#endif

}  // namespace

void BlockRowBounds::reset(int blocks_x) {
  avx2 = process_isa() >= Isa::avx2;
  acc.assign(size_t(blocks_x), BlockBounds{});
  nan.assign(size_t(blocks_x), 0);
  used.assign(size_t(blocks_x), 0);
  lanes.resize(size_t(blocks_x) * 48);
}

void BlockRowBounds::add_row(const vec3* pos, const uint8_t* cov, int width) {
  static_assert(sizeof(vec3) == 12, "packed vec3");
  for (size_t b = 0; b < acc.size(); ++b) {
    const int x0 = int(b) * kGBufferBlock, x1 = std::min(width, x0 + kGBufferBlock);
#if defined(__x86_64__)
    if (avx2 && x1 - x0 == kGBufferBlock) {
      uint64_t c[2];
      std::memcpy(c, cov + x0, 16);
      if (c[0] == 0x0101010101010101ull && c[1] == 0x0101010101010101ull) {
        if (!used[b]) {
          std::fill_n(&lanes[48 * b], 24, kInf);
          std::fill_n(&lanes[48 * b + 24], 24, -kInf);
          used[b] = 1;
        }
        nan[b] |= uint8_t(add_full_segment_avx2(&pos[x0].x, &lanes[48 * b]));
        continue;
      }
    }
#endif
    vec3 lo = acc[b].lo, hi = acc[b].hi;
    bool bad = false;
    for (int x = x0; x < x1; ++x) {
      if (!cov[x]) continue;
      const vec3 p = pos[x];
      bad |= (p.x != p.x) | (p.y != p.y) | (p.z != p.z);
      for (int k = 0; k < 3; ++k) {
        lo[k] = p[k] < lo[k] ? p[k] : lo[k];
        hi[k] = p[k] > hi[k] ? p[k] : hi[k];
      }
    }
    acc[b].lo = lo;
    acc[b].hi = hi;
    nan[b] |= uint8_t(bad);
  }
}

void BlockRowBounds::store(GBuffer& g, int by) const {
  for (size_t b = 0; b < acc.size(); ++b) {
    BlockBounds out = acc[b];
#if defined(__x86_64__)
    // The AVX2 path's lanes (set only on that path). Minima and maxima of equal values are
    // order-independent except for the sign of a zero, which no consumer looks at.
    if (used[b])
      for (int c = 0; c < 3; ++c) {
        const float l = fold_component<false>(&lanes[48 * b], c, kInf);
        const float h = fold_component<true>(&lanes[48 * b + 24], c, -kInf);
        out.lo[c] = l < out.lo[c] ? l : out.lo[c];
        out.hi[c] = h > out.hi[c] ? h : out.hi[c];
      }
#endif
    if (nan[b]) {
      out.lo = vec3(-kInf);
      out.hi = vec3(kInf);
    }
    g.block_bounds[size_t(by) * acc.size() + b] = out;
  }
}

void compute_block_bounds(GBuffer& g, int y0, int y1) {
  if (!g.has_block_bounds())
    g.block_bounds.assign(size_t(g.blocks_x()) * size_t(g.blocks_y()), BlockBounds{});
  BlockRowBounds row;
  for (int by = y0 / kGBufferBlock; by * kGBufferBlock < y1; ++by) {
    row.reset(g.blocks_x());
    const int ye = std::min(y1, (by + 1) * kGBufferBlock);
    for (int y = by * kGBufferBlock; y < ye; ++y) {
      const size_t i = size_t(y) * size_t(g.width);
      row.add_row(&g.position[i], &g.covered[i], g.width);
    }
    row.store(g, by);
  }
}

void compute_block_bounds(GBuffer& g) { compute_block_bounds(g, 0, g.height); }

}  // namespace shadowlab
