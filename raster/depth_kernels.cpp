#include "raster/depth_kernels.h"

#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

namespace shadowlab {

void depth_row8_scalar(const int64_t edge[3], const int64_t step_x[3], float zy, float z_dx,
                       int ox, float* z) {
  int64_t e0 = edge[0], e1 = edge[1], e2 = edge[2];
  for (int i = 0; i < 8; ++i) {
    if ((e0 | e1 | e2) >= 0) {
      const float iw = zy + z_dx * float(ox + i);
      if (iw > z[i]) z[i] = iw;
    }
    e0 += step_x[0];
    e1 += step_x[1];
    e2 += step_x[2];
  }
}

void depth_block8_scalar(const DepthBlock8& b, float* z, size_t stride) {
  int64_t edge[3] = {b.edge[0], b.edge[1], b.edge[2]};
  for (int r = 0; r < b.rows; ++r) {
    const float zy = b.z0 + b.z_dy * float(b.oy + r);
    depth_row8_scalar(edge, b.step_x, zy, b.z_dx, b.ox, z + size_t(r) * stride);
    for (int k = 0; k < 3; ++k) edge[k] += b.step_y[k];
  }
}

#ifdef SHADOWLAB_HAVE_X86
__attribute__((target("avx2"))) static void depth_block8_avx2_impl(const DepthBlock8& b, float* z,
                                                                   size_t stride) {
  // Per edge, lanes 0-3 and 4-7 of the first row; each row adds step_y to every lane.
  __m256i lo[3], hi[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    const int64_t e = b.edge[k], s = b.step_x[k];
    lo[k] = _mm256_set_epi64x(e + 3 * s, e + 2 * s, e + s, e);
    hi[k] = _mm256_set_epi64x(e + 7 * s, e + 6 * s, e + 5 * s, e + 4 * s);
    dy[k] = _mm256_set1_epi64x(b.step_y[k]);
  }
  const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256 x = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(b.ox),
                                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m256 zx = _mm256_mul_ps(_mm256_set1_ps(b.z_dx), x);  // z_dx * float(ox + i)
  for (int r = 0; r < b.rows; ++r) {
    const __m256i l = _mm256_or_si256(_mm256_or_si256(lo[0], lo[1]), lo[2]);
    const __m256i h = _mm256_or_si256(_mm256_or_si256(hi[0], hi[1]), hi[2]);
    const int out_bits = _mm256_movemask_pd(_mm256_castsi256_pd(l)) |
                         (_mm256_movemask_pd(_mm256_castsi256_pd(h)) << 4);
    if (out_bits != 0xFF) {
      const __m256i covered = _mm256_cmpeq_epi32(
          _mm256_and_si256(_mm256_set1_epi32(~out_bits), lane_bit), lane_bit);
      const float zy = b.z0 + b.z_dy * float(b.oy + r);
      const __m256 iw = _mm256_add_ps(_mm256_set1_ps(zy), zx);
      float* row = z + size_t(r) * stride;
      const __m256 old = _mm256_loadu_ps(row);
      const __m256 nearer =
          _mm256_and_ps(_mm256_cmp_ps(iw, old, _CMP_GT_OQ), _mm256_castsi256_ps(covered));
      _mm256_storeu_ps(row, _mm256_blendv_ps(old, iw, nearer));
    }
    for (int k = 0; k < 3; ++k) {
      lo[k] = _mm256_add_epi64(lo[k], dy[k]);
      hi[k] = _mm256_add_epi64(hi[k], dy[k]);
    }
  }
}

__attribute__((target("avx2"))) static void depth_row8_avx2_impl(const int64_t edge[3],
                                                                 const int64_t step_x[3], float zy,
                                                                 float z_dx, int ox, float* z) {
  // Lanes 0-3 and 4-7 of each edge: edge + step·i, exact in int64.
  __m256i lo = _mm256_setzero_si256(), hi = _mm256_setzero_si256();
  for (int k = 0; k < 3; ++k) {
    const int64_t e = edge[k], s = step_x[k];
    const __m256i l = _mm256_set_epi64x(e + 3 * s, e + 2 * s, e + s, e);
    const __m256i h = _mm256_set_epi64x(e + 7 * s, e + 6 * s, e + 5 * s, e + 4 * s);
    lo = _mm256_or_si256(lo, l);
    hi = _mm256_or_si256(hi, h);
  }
  // Sign bit of (e0|e1|e2) set = outside some edge. 8-bit mask of covered lanes.
  const int out_bits = _mm256_movemask_pd(_mm256_castsi256_pd(lo)) |
                       (_mm256_movemask_pd(_mm256_castsi256_pd(hi)) << 4);
  if (out_bits == 0xFF) return;
  const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i covered = _mm256_cmpeq_epi32(
      _mm256_and_si256(_mm256_set1_epi32(~out_bits), lane_bit), lane_bit);
  // Depth plane, same operations as the scalar oracle: zy + z_dx * float(ox + i).
  const __m256 x = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(ox),
                                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m256 iw = _mm256_add_ps(_mm256_set1_ps(zy), _mm256_mul_ps(_mm256_set1_ps(z_dx), x));
  const __m256 old = _mm256_loadu_ps(z);
  const __m256 nearer = _mm256_and_ps(_mm256_cmp_ps(iw, old, _CMP_GT_OQ), _mm256_castsi256_ps(covered));
  _mm256_storeu_ps(z, _mm256_blendv_ps(old, iw, nearer));
}
#endif

DepthRow8Fn depth_row8_avx2() {
#ifdef SHADOWLAB_HAVE_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) return depth_row8_avx2_impl;
#endif
  return nullptr;
}

DepthBlock8Fn depth_block8_avx2() {
#ifdef SHADOWLAB_HAVE_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) return depth_block8_avx2_impl;
#endif
  return nullptr;
}

DepthBlock8Fn depth_block8_selected() {
  const char* force = std::getenv("SHADOWLAB_SCALAR");
  if (force && std::strcmp(force, "1") == 0) return depth_block8_scalar;
  const DepthBlock8Fn fast = depth_block8_avx2();
  return fast ? fast : depth_block8_scalar;
}

DepthRow8Fn depth_row8_selected() {
  const char* force = std::getenv("SHADOWLAB_SCALAR");
  if (force && std::strcmp(force, "1") == 0) return depth_row8_scalar;
  const DepthRow8Fn fast = depth_row8_avx2();
  return fast ? fast : depth_row8_scalar;
}

const char* depth_kernel_name() {
  return depth_row8_selected() == depth_row8_scalar ? "scalar" : "avx2";
}

}  // namespace shadowlab
