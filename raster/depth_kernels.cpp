#include "raster/depth_kernels.h"

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/isa.h"
#include "core/simd_target.h"
#include "raster/setup.h"

namespace shadowlab {

namespace {


// Block j's skip and whole-coverage tests (edge values e at its first pixel). Each is one
// test of the three values' OR (a sign bit set in any of them), not a chain of three branches:
// the outcomes are data-dependent, and the chains' branches were the most mispredicted of the
// cube (callgrind --branch-sim).
bool row_block(const DepthRow8& r, const int64_t* e, bool& inside) {
  if (((e[0] + r.hi_off[0]) | (e[1] + r.hi_off[1]) | (e[2] + r.hi_off[2])) < 0) return false;
  inside = ((e[0] + r.lo_off[0]) | (e[1] + r.lo_off[1]) | (e[2] + r.lo_off[2])) >= 0;
  return true;
}

}  // namespace

void depth_row8_scalar(const DepthRow8& r, float* z, size_t stride) {
  for (int j = 0; j < r.blocks; ++j) {
    float* const zb = z + 8 * size_t(j);
    uint32_t* const idb = r.ids ? r.ids + 8 * size_t(j) : nullptr;
    const int ox = r.ox + 8 * j;
    for (int row = 0; row < r.rows; ++row) {
      const float zy = r.z0 + r.z_dy * float(r.oy + row);
      float* const zr = zb + size_t(row) * stride;
      int64_t e[3];
      for (int k = 0; k < 3; ++k)
        e[k] = r.edge[k] + r.block_step[k] * j + r.step_y[k] * int64_t(row);
      for (int i = 0; i < 8; ++i, e[0] += r.step_x[0], e[1] += r.step_x[1], e[2] += r.step_x[2]) {
        if ((e[0] | e[1] | e[2]) < 0) continue;
        const float iw = std::min(std::max(zy + r.z_dx * float(ox + i), r.z_lo), r.z_hi);
        if (iw > zr[i]) {
          zr[i] = iw;
          if (idb) idb[size_t(row) * stride + size_t(i)] = r.id;
        }
      }
    }
  }
}

#ifdef SHADOWLAB_HAVE_X86
#define SL_AVX2 SL_TARGET("avx2")
#define SL_AVX512 SL_TARGET("avx512f,avx512vl,avx512dq")

// The plane's x term of a block's 8 lanes: z_dx * float(ox + i).
SL_AVX2 inline __m256 plane_x_avx2(float z_dx, int ox) {
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
// are neither read nor stepped (lo, hi and dy may be null). A loop of its own drops the coverage mask's four operations per row, which
// are all ones there: 3 % of this kernel's instructions on room100k's cube at 2048, where
// inside blocks carry most pixels.
template <bool kInside>
SL_AVX2 inline void block_rows_avx2(__m256i* lo, __m256i* hi, const __m256i* dy, __m256 zx,
                                    const PlaneRows& p, __m256 z_lo, __m256 z_hi, __m256 id,
                                    float* z, uint32_t* ids, size_t stride) {
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
      const __m256i covered = _mm256_cmpeq_epi32(
          _mm256_and_si256(_mm256_set1_epi32(~out_bits), lane_bit), lane_bit);
      nearer = _mm256_and_ps(nearer, _mm256_castsi256_ps(covered));
    }
    _mm256_storeu_ps(row, _mm256_blendv_ps(old, iw, nearer));
    if (ids) {
      float* idr = reinterpret_cast<float*>(ids + size_t(r) * stride);
      _mm256_storeu_ps(idr, _mm256_blendv_ps(_mm256_loadu_ps(idr), id, nearer));
    }
  }
}

// The AVX2 row of blocks: block_rows_avx2 per block, the lane offsets step_x · i made once per
// row (exact int64 sums: the values of lane_x).
SL_AVX2 static void depth_row8_avx2_impl(const DepthRow8& rw, float* z, size_t stride) {
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
      const __m256 zx = plane_x_avx2(rw.z_dx, rw.ox + 8 * j);
      float* const zb = z + 8 * size_t(j);
      uint32_t* const idb = rw.ids ? rw.ids + 8 * size_t(j) : nullptr;
      if (inside) {  // no edge values needed
        block_rows_avx2<true>(nullptr, nullptr, nullptr, zx, p, z_lo, z_hi, id, zb, idb, stride);
      } else {
        __m256i lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
          const __m256i ek = _mm256_set1_epi64x(e[k]);
          lo[k] = _mm256_add_epi64(ek, lane_lo[k]);
          hi[k] = _mm256_add_epi64(ek, lane_hi[k]);
        }
        block_rows_avx2<false>(lo, hi, dy, zx, p, z_lo, z_hi, id, zb, idb, stride);
      }
    }
    for (int k = 0; k < 3; ++k) e[k] += rw.block_step[k];
  }
}

// The rows of one block, AVX-512: ev holds each edge's 8 lanes at the first row; `lanes` the
// lanes that are pixels (all but in a block cut by the viewport's right edge, whose other lanes
// are neither read nor written). Covered lanes and the depth test are mask registers, stores are
// masked; no branch on a row's coverage (as block_rows_avx2).
SL_AVX512 inline void block_rows_avx512(__m512i* ev, const __m512i* dy, bool inside,
                                        __mmask8 lanes, __m256 zx, const PlaneRows& p,
                                        __m256 z_lo, __m256 z_hi, __m256i id, float* z,
                                        uint32_t* ids, size_t stride) {
  const __m512i zero = _mm512_setzero_si512();
  for (int r = 0; r < p.rows; ++r) {
    __mmask8 covered = lanes;
    if (!inside) {
      const __m512i any = _mm512_or_si512(_mm512_or_si512(ev[0], ev[1]), ev[2]);
      covered = __mmask8(covered & _mm512_cmpge_epi64_mask(any, zero));
      for (int k = 0; k < 3; ++k) ev[k] = _mm512_add_epi64(ev[k], dy[k]);
    }
    const float zy = p.z0 + p.z_dy * float(p.oy + r);
    const __m256 iw =
        _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_set1_ps(zy), zx), z_lo), z_hi);
    float* row = z + size_t(r) * stride;
    const __mmask8 nearer =
        _mm256_mask_cmp_ps_mask(covered, iw, _mm256_maskz_loadu_ps(covered, row), _CMP_GT_OQ);
    _mm256_mask_storeu_ps(row, nearer, iw);
    if (ids) _mm256_mask_storeu_epi32(ids + size_t(r) * stride, nearer, id);
  }
}

// A triangle's whole walk in a tile (rasterize_depth_in_rect's, in registers) with
// block_rows_avx512 per block; the lane offsets step_x · i once per triangle (vpmullq: the same
// exact int64 products as lane_x).
SL_AVX512 static void depth_triangle_avx512_impl(const TriangleSetup& s, int x0, int y0, int x1,
                                                 int y1, float* z, uint32_t* ids, size_t width) {
  const int min_x = std::max(s.min_x, x0), max_x = std::min(s.max_x, x1 - 1);
  const int min_y = std::max(s.min_y, y0), max_y = std::min(s.max_y, y1 - 1);
  if (min_x > max_x || min_y > max_y) return;
  constexpr int kBlock = 8;
  const int64_t one = int64_t(1) << kSubpixelBits, half = one / 2;
  const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
  int64_t step_x[3], step_y[3], bstep[3], x_span[3];
  __m512i lane[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    step_x[k] = s.a[k] * one;
    step_y[k] = s.b[k] * one;
    bstep[k] = step_x[k] * kBlock;
    x_span[k] = step_x[k] * (kBlock - 1);
    lane[k] = _mm512_mullo_epi64(_mm512_set1_epi64(step_x[k]), iota);
    dy[k] = _mm512_set1_epi64(step_y[k]);
  }
  const __m256 z_lo = _mm256_set1_ps(s.z_lo), z_hi = _mm256_set1_ps(s.z_hi);
  const __m256i id = _mm256_set1_epi32(int(s.triangle));
  const int bx_start = min_x - (min_x - x0) % kBlock;
  const int by_start = min_y - (min_y - y0) % kBlock;
  for (int by = by_start; by <= max_y; by += kBlock) {
    const int py0 = std::max(by, min_y), py1 = std::min(by + kBlock - 1, max_y);
    const PlaneRows p{s.z0, s.z_dy, py0 - s.min_y, py1 - py0 + 1};
    int64_t e[3], lo_off[3], hi_off[3];
    for (int k = 0; k < 3; ++k) {
      e[k] = s.a[k] * (int64_t(bx_start) * one + half) + s.b[k] * (int64_t(py0) * one + half) +
             s.c[k];
      const int64_t d = step_y[k] * int64_t(py1 - py0);
      lo_off[k] = std::min<int64_t>(0, x_span[k]) + std::min<int64_t>(0, d);
      hi_off[k] = std::max<int64_t>(0, x_span[k]) + std::max<int64_t>(0, d);
    }
    float* const zrow = z + size_t(py0) * width;
    uint32_t* const idrow = ids ? ids + size_t(py0) * width : nullptr;
    for (int bx = bx_start; bx <= max_x;
         bx += kBlock, e[0] += bstep[0], e[1] += bstep[1], e[2] += bstep[2]) {
      if (e[0] + hi_off[0] < 0 || e[1] + hi_off[1] < 0 || e[2] + hi_off[2] < 0) continue;
      const bool inside =
          e[0] + lo_off[0] >= 0 && e[1] + lo_off[1] >= 0 && e[2] + lo_off[2] >= 0;
      // The viewport's right edge: lanes from x1 on are not pixels.
      const __mmask8 lanes =
          bx + kBlock > x1 ? __mmask8((1u << (x1 - bx)) - 1u) : __mmask8(0xFF);
      __m512i ev[3];
      for (int k = 0; k < 3; ++k) ev[k] = _mm512_add_epi64(_mm512_set1_epi64(e[k]), lane[k]);
      block_rows_avx512(ev, dy, inside, lanes, plane_x_avx2(s.z_dx, bx - s.min_x), p, z_lo, z_hi,
                        id, zrow + bx, idrow ? idrow + bx : nullptr, width);
    }
  }
}

#undef SL_AVX512
#undef SL_AVX2
#endif

DepthTriangleFn depth_triangle_avx512() {
#ifdef SHADOWLAB_HAVE_X86
  if (cpu_isa() == Isa::avx512) return depth_triangle_avx512_impl;
#endif
  return nullptr;
}

DepthTriangleFn depth_triangle_selected() {
  return process_isa() == Isa::avx512 ? depth_triangle_avx512() : nullptr;
}

DepthRow8Fn depth_row8_avx2() {
#ifdef SHADOWLAB_HAVE_X86
  if (cpu_isa() >= Isa::avx2) return depth_row8_avx2_impl;
#endif
  return nullptr;
}

DepthRow8Fn depth_row8_selected() {
  // The AVX-512 path walks whole triangles (depth_triangle_avx512); rows of blocks in AVX2.
  const DepthRow8Fn avx2 = process_isa() == Isa::scalar ? nullptr : depth_row8_avx2();
  return avx2 ? avx2 : depth_row8_scalar;
}

const char* depth_kernel_name() {
  return isa_name(process_isa());
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SHADOWLAB_HAVE_X86
