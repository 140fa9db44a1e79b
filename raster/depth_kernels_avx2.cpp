// The AVX2 row of blocks of raster/depth_kernels.h (the AVX-512 table uses it too, beside its
// whole-triangle walk). Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "raster/depth_kernels.h"

namespace shadowlab::depth_kernels_avx2 {

// Block j's skip and whole-coverage tests (edge values e at its first pixel). Each is one
// test of the three values' OR (a sign bit set in any of them), not a chain of three branches:
// the outcomes are data-dependent, and the chains' branches were the most mispredicted of the
// cube (callgrind --branch-sim).
[[gnu::always_inline]] inline bool row_block(const DepthRow8& r, const int64_t* e, bool& inside) {
  if (((e[0] + r.hi_off[0]) | (e[1] + r.hi_off[1]) | (e[2] + r.hi_off[2])) < 0) return false;
  inside = ((e[0] + r.lo_off[0]) | (e[1] + r.lo_off[1]) | (e[2] + r.lo_off[2])) >= 0;
  return true;
}

// The plane's x term of a block's 8 lanes: z_dx * float(ox + i).
[[gnu::always_inline]] inline __m256 plane_x(float z_dx, int ox) {
  const __m256 x = _mm256_cvtepi32_ps(
      _mm256_add_epi32(_mm256_set1_epi32(ox), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  return _mm256_mul_ps(_mm256_set1_ps(z_dx), x);
}

// What a block's rows share, in registers: the stores may alias the caller's records as far as
// the compiler knows, which would otherwise reload every field on every row.
struct PlaneRows {
  float z0, z_dy;
  int oy, rows;
};

// The rows of one block, AVX2: lo/hi hold each edge's lanes 0-3 and 4-7 at the first row, and
// every row adds step_y (dy) to them. A row with no covered lane still runs its (then empty)
// blend and store: a branch there was mispredicted on the small triangles' partial rows.
// kInside: the block lies inside all three edges, so every lane is covered and the edge values
// are neither read nor stepped (lo, hi and dy may be null). A loop of its own drops the coverage
// mask's four operations per row, which are all ones there: 3 % of this kernel's instructions on
// room100k's cube at 2048, where inside blocks carry most pixels.
template <bool kInside>
[[gnu::always_inline]] inline void block_rows(__m256i* lo, __m256i* hi, const __m256i* dy,
                                              __m256 zx, const PlaneRows& p, __m256 z_lo,
                                              __m256 z_hi, __m256 id, float* z, uint32_t* ids,
                                              size_t stride) {
  const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  for (int r = 0; r < p.rows; ++r) {
    const float zy = p.z0 + p.z_dy * float(p.oy + r);
    const __m256 iw =
        _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_set1_ps(zy), zx), z_lo), z_hi);
    float* row = z + size_t(r) * stride;
    const __m256 old = _mm256_loadu_ps(row);
    __m256 nearer = _mm256_cmp_ps(iw, old, _CMP_GT_OQ);
    if constexpr (!kInside) {
      const __m256i l = _mm256_or_si256(_mm256_or_si256(lo[0], lo[1]), lo[2]);
      const __m256i h = _mm256_or_si256(_mm256_or_si256(hi[0], hi[1]), hi[2]);
      const int out_bits = _mm256_movemask_pd(_mm256_castsi256_pd(l)) |
                           (_mm256_movemask_pd(_mm256_castsi256_pd(h)) << 4);
      for (int k = 0; k < 3; ++k) {
        lo[k] = _mm256_add_epi64(lo[k], dy[k]);
        hi[k] = _mm256_add_epi64(hi[k], dy[k]);
      }
      const __m256i covered =
          _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(~out_bits), lane_bit), lane_bit);
      nearer = _mm256_and_ps(nearer, _mm256_castsi256_ps(covered));
    }
    _mm256_storeu_ps(row, _mm256_blendv_ps(old, iw, nearer));
    if (ids) {
      float* idr = reinterpret_cast<float*>(ids + size_t(r) * stride);
      _mm256_storeu_ps(idr, _mm256_blendv_ps(_mm256_loadu_ps(idr), id, nearer));
    }
  }
}

// The AVX2 row of blocks: block_rows per block, the lane offsets step_x · i made once per
// row (exact int64 sums: the values of lane_x).
void row8(const DepthRow8& rw, float* z, size_t stride) {
  __m256i lane_lo[3], lane_hi[3], dy[3];
  int64_t e[3];
  for (int k = 0; k < 3; ++k) {
    const int64_t s1 = rw.step_x[k], s2 = s1 + s1, s3 = s2 + s1, s4 = s2 + s2;
    lane_lo[k] = _mm256_setr_epi64x(0, s1, s2, s3);
    lane_hi[k] = _mm256_add_epi64(lane_lo[k], _mm256_set1_epi64x(s4));
    dy[k] = _mm256_set1_epi64x(rw.step_y[k]);
    e[k] = rw.edge[k];
  }
  const PlaneRows p{rw.z0, rw.z_dy, rw.oy, rw.rows};
  const __m256 z_lo = _mm256_set1_ps(rw.z_lo), z_hi = _mm256_set1_ps(rw.z_hi);
  const __m256 id = _mm256_castsi256_ps(_mm256_set1_epi32(int(rw.id)));
  for (int j = 0; j < rw.blocks; ++j) {
    bool inside = false;
    if (row_block(rw, e, inside)) {
      const __m256 zx = plane_x(rw.z_dx, rw.ox + 8 * j);
      float* const zb = z + 8 * size_t(j);
      uint32_t* const idb = rw.ids ? rw.ids + 8 * size_t(j) : nullptr;
      if (inside) {  // no edge values needed
        block_rows<true>(nullptr, nullptr, nullptr, zx, p, z_lo, z_hi, id, zb, idb, stride);
      } else {
        __m256i lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
          const __m256i ek = _mm256_set1_epi64x(e[k]);
          lo[k] = _mm256_add_epi64(ek, lane_lo[k]);
          hi[k] = _mm256_add_epi64(ek, lane_hi[k]);
        }
        block_rows<false>(lo, hi, dy, zx, p, z_lo, z_hi, id, zb, idb, stride);
      }
    }
    for (int k = 0; k < 3; ++k) e[k] += rw.block_step[k];
  }
}

}  // namespace shadowlab::depth_kernels_avx2
#endif
