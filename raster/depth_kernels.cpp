#include "raster/depth_kernels.h"

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/cpu_features.h"

namespace shadowlab {

void depth_block8_scalar(const DepthBlock8& b, float* z, size_t stride) {
  int64_t row[3] = {b.edge[0], b.edge[1], b.edge[2]};
  for (int r = 0; r < b.rows; ++r) {
    const float zy = b.z0 + b.z_dy * float(b.oy + r);
    float* zr = z + size_t(r) * stride;
    uint32_t* idr = b.ids ? b.ids + size_t(r) * stride : nullptr;
    int64_t e0 = row[0], e1 = row[1], e2 = row[2];
    for (int i = 0; i < 8; ++i) {
      if ((e0 | e1 | e2) >= 0) {
        const float iw = std::min(std::max(zy + b.z_dx * float(b.ox + i), b.z_lo), b.z_hi);
        if (iw > zr[i]) {
          zr[i] = iw;
          if (idr) idr[i] = b.id;
        }
      }
      e0 += b.step_x[0];
      e1 += b.step_x[1];
      e2 += b.step_x[2];
    }
    for (int k = 0; k < 3; ++k) row[k] += b.step_y[k];
  }
}

#ifdef SHADOWLAB_HAVE_X86
__attribute__((target("avx2"))) static void depth_block8_avx2_impl(const DepthBlock8& b, float* z,
                                                                   size_t stride) {
  // Per edge, lanes 0-3 and 4-7 of the first row; each row adds step_y to every lane.
  __m256i lo[3], hi[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    const __m256i e = _mm256_set1_epi64x(b.edge[k]);
    lo[k] = _mm256_add_epi64(e, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b.lane_x[k])));
    hi[k] = _mm256_add_epi64(e, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b.lane_x[k] + 4)));
    dy[k] = _mm256_set1_epi64x(b.step_y[k]);
  }
  const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256 x = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(b.ox),
                                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m256 zx = _mm256_mul_ps(_mm256_set1_ps(b.z_dx), x);  // z_dx * float(ox + i)
  // Everything the rows need, in registers: the stores below may alias `b` as far as the
  // compiler knows, which would otherwise reload every field on every row.
  const float z0 = b.z0, z_dy = b.z_dy;
  const __m256 z_lo = _mm256_set1_ps(b.z_lo), z_hi = _mm256_set1_ps(b.z_hi);
  const __m256 id = _mm256_castsi256_ps(_mm256_set1_epi32(int(b.id)));
  uint32_t* const ids = b.ids;
  const bool inside = b.inside;
  const int rows = b.rows, oy = b.oy;
  for (int r = 0; r < rows; ++r) {
    int out_bits = 0;
    if (!inside) {
      const __m256i l = _mm256_or_si256(_mm256_or_si256(lo[0], lo[1]), lo[2]);
      const __m256i h = _mm256_or_si256(_mm256_or_si256(hi[0], hi[1]), hi[2]);
      out_bits = _mm256_movemask_pd(_mm256_castsi256_pd(l)) |
                 (_mm256_movemask_pd(_mm256_castsi256_pd(h)) << 4);
    }
    if (out_bits != 0xFF) {
      const __m256i covered = _mm256_cmpeq_epi32(
          _mm256_and_si256(_mm256_set1_epi32(~out_bits), lane_bit), lane_bit);
      const float zy = z0 + z_dy * float(oy + r);
      const __m256 iw = _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_set1_ps(zy), zx), z_lo), z_hi);
      float* row = z + size_t(r) * stride;
      const __m256 old = _mm256_loadu_ps(row);
      const __m256 nearer =
          _mm256_and_ps(_mm256_cmp_ps(iw, old, _CMP_GT_OQ), _mm256_castsi256_ps(covered));
      _mm256_storeu_ps(row, _mm256_blendv_ps(old, iw, nearer));
      if (ids) {
        float* idr = reinterpret_cast<float*>(ids + size_t(r) * stride);
        _mm256_storeu_ps(idr, _mm256_blendv_ps(_mm256_loadu_ps(idr), id, nearer));
      }
    }
    if (!inside)
      for (int k = 0; k < 3; ++k) {
        lo[k] = _mm256_add_epi64(lo[k], dy[k]);
        hi[k] = _mm256_add_epi64(hi[k], dy[k]);
      }
  }
}

// The AVX-512 form of the AVX2 kernel: each edge's 8 lanes in one register, the covered lanes
// and the depth test as mask registers, masked stores where the AVX2 kernel blends. The same
// integer and IEEE float operations per lane (the plane value, its clamp, the > test), so the
// same bits (tests/raster/depth_kernels_test.cpp).
__attribute__((target("avx512f,avx512vl,avx512dq"))) static void depth_block8_avx512_impl(
    const DepthBlock8& b, float* z, size_t stride) {
  __m512i e[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    e[k] = _mm512_add_epi64(_mm512_set1_epi64(b.edge[k]), _mm512_loadu_si512(b.lane_x[k]));
    dy[k] = _mm512_set1_epi64(b.step_y[k]);
  }
  const __m256 x = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(b.ox),
                                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m256 zx = _mm256_mul_ps(_mm256_set1_ps(b.z_dx), x);  // z_dx * float(ox + i)
  const float z0 = b.z0, z_dy = b.z_dy;
  const __m256 z_lo = _mm256_set1_ps(b.z_lo), z_hi = _mm256_set1_ps(b.z_hi);
  const __m256i id = _mm256_set1_epi32(int(b.id));
  uint32_t* const ids = b.ids;
  const bool inside = b.inside;
  const int rows = b.rows, oy = b.oy;
  const __m512i zero = _mm512_setzero_si512();
  for (int r = 0; r < rows; ++r) {
    __mmask8 covered = 0xFF;
    if (!inside) {
      const __m512i any = _mm512_or_si512(_mm512_or_si512(e[0], e[1]), e[2]);
      covered = _mm512_cmpge_epi64_mask(any, zero);
      for (int k = 0; k < 3; ++k) e[k] = _mm512_add_epi64(e[k], dy[k]);
    }
    if (covered) {
      const float zy = z0 + z_dy * float(oy + r);
      const __m256 iw = _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_set1_ps(zy), zx), z_lo), z_hi);
      float* row = z + size_t(r) * stride;
      const __mmask8 nearer = _mm256_mask_cmp_ps_mask(covered, iw, _mm256_loadu_ps(row), _CMP_GT_OQ);
      _mm256_mask_storeu_ps(row, nearer, iw);
      if (ids) _mm256_mask_storeu_epi32(ids + size_t(r) * stride, nearer, id);
    }
  }
}

#endif

DepthBlock8Fn depth_block8_avx512() {
#ifdef SHADOWLAB_HAVE_X86
  if (cpu_has_avx512()) return depth_block8_avx512_impl;
#endif
  return nullptr;
}

DepthBlock8Fn depth_block8_avx2() {
#ifdef SHADOWLAB_HAVE_X86
  if (cpu_has_avx2()) return depth_block8_avx2_impl;
#endif
  return nullptr;
}

DepthBlock8Fn depth_block8_selected() {
  if (use_avx512_paths())
    if (const DepthBlock8Fn f = depth_block8_avx512()) return f;
  const DepthBlock8Fn fast = use_avx2_paths() ? depth_block8_avx2() : nullptr;
  return fast ? fast : depth_block8_scalar;
}

const char* depth_kernel_name() {
  const DepthBlock8Fn f = depth_block8_selected();
  return f == depth_block8_scalar ? "scalar" : f == depth_block8_avx2() ? "avx2" : "avx512";
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SHADOWLAB_HAVE_X86
