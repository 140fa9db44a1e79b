// The AVX2 form of raster/vertex_transform.h (the AVX-512 table uses it too). Compiled with
// -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "core/math.h"
#include "raster/clip.h"

namespace shadowlab {

void transform_vertices_scalar(const mat4& m, const vec3* pos, size_t n, float guard_x,
                               float guard_y, vec4* clip, uint32_t* code);

namespace vertex_transform_avx2 {

// Bit `bit` in the lanes where d < 0 (ordered: a NaN distance sets nothing; non-finite
// vertices are replaced by kOutNonFinite anyway).
[[gnu::always_inline]] inline __m256i bit_if_negative(__m256 d, uint32_t bit) {
  const __m256 neg = _mm256_cmp_ps(d, _mm256_setzero_ps(), _CMP_LT_OQ);
  return _mm256_and_si256(_mm256_castps_si256(neg), _mm256_set1_epi32(int(bit)));
}

void transform(const mat4& m, const vec3* pos, size_t n, float guard_x, float guard_y, vec4* clip,
               uint32_t* code) {
  static_assert(sizeof(vec3) == 12 && sizeof(vec4) == 16, "packed glm vectors");
  const size_t full = n - n % 8;
  const float* p = reinterpret_cast<const float*>(pos);  // packed x, y, z (no access when n = 0)
  // Lane k reads vertex k's x, y and z: floats 3k, 3k + 1, 3k + 2 of the batch.
  const __m256i idx = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  // m's 16 floats, column-major (glm): m[c][r] at mf[4c + r] (no glm function in this file).
  const float* mf = reinterpret_cast<const float*>(&m);
  __m256 mc[4][4];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) mc[c][r] = _mm256_set1_ps(mf[4 * c + r]);
  const __m256 gx = _mm256_set1_ps(guard_x), gy = _mm256_set1_ps(guard_y);
  const __m256i exp_mask = _mm256_set1_epi32(0x7F800000);
  for (size_t i = 0; i < full; i += 8) {
    const float* b = p + 3 * i;
    const __m256 x = _mm256_i32gather_ps(b, idx, 4);
    const __m256 y = _mm256_i32gather_ps(b + 1, idx, 4);
    const __m256 z = _mm256_i32gather_ps(b + 2, idx, 4);
    __m256 o[4];  // clip x, y, z, w
    for (int r = 0; r < 4; ++r) {
      const __m256 a0 = _mm256_add_ps(_mm256_mul_ps(mc[0][r], x), _mm256_mul_ps(mc[1][r], y));
      const __m256 a1 = _mm256_add_ps(_mm256_mul_ps(mc[2][r], z), mc[3][r]);  // m3 · 1 = m3
      o[r] = _mm256_add_ps(a0, a1);
    }
    // Outcodes: clip.cpp's plane distances, bits 0..4 against the viewport (guard 1: 1·w = w)
    // and 5..9 against the guard band.
    const __m256 w = o[3];
    const __m256 near = _mm256_add_ps(o[2], w);
    const __m256 gxw = _mm256_mul_ps(gx, w), gyw = _mm256_mul_ps(gy, w);
    __m256i c = _mm256_or_si256(bit_if_negative(near, 1u << 0), bit_if_negative(near, 1u << 5));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_sub_ps(w, o[0]), 1u << 1));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_add_ps(w, o[0]), 1u << 2));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_sub_ps(w, o[1]), 1u << 3));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_add_ps(w, o[1]), 1u << 4));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_sub_ps(gxw, o[0]), 1u << 6));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_add_ps(gxw, o[0]), 1u << 7));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_sub_ps(gyw, o[1]), 1u << 8));
    c = _mm256_or_si256(c, bit_if_negative(_mm256_add_ps(gyw, o[1]), 1u << 9));
    // A lane with an all-ones exponent in any coordinate (NaN or infinite) gets kOutNonFinite.
    __m256i bad = _mm256_setzero_si256();
    for (int r = 0; r < 4; ++r) {
      const __m256i e = _mm256_and_si256(_mm256_castps_si256(o[r]), exp_mask);
      bad = _mm256_or_si256(bad, _mm256_cmpeq_epi32(e, exp_mask));
    }
    c = _mm256_blendv_epi8(c, _mm256_set1_epi32(int(kOutNonFinite)), bad);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(code + i), c);
    // 4 × 8 → 8 × 4: vertex k's (x, y, z, w) to clip[i + k].
    const __m256 t0 = _mm256_unpacklo_ps(o[0], o[1]);  // x0 y0 x1 y1 | x4 y4 x5 y5
    const __m256 t1 = _mm256_unpackhi_ps(o[0], o[1]);  // x2 y2 x3 y3 | x6 y6 x7 y7
    const __m256 t2 = _mm256_unpacklo_ps(o[2], o[3]);  // z0 w0 z1 w1 | …
    const __m256 t3 = _mm256_unpackhi_ps(o[2], o[3]);
    const __m256 v01 = _mm256_shuffle_ps(t0, t2, 0x44);  // vertex 0 | vertex 4
    const __m256 v11 = _mm256_shuffle_ps(t0, t2, 0xEE);  // vertex 1 | vertex 5
    const __m256 v22 = _mm256_shuffle_ps(t1, t3, 0x44);  // vertex 2 | vertex 6
    const __m256 v33 = _mm256_shuffle_ps(t1, t3, 0xEE);  // vertex 3 | vertex 7
    float* out = reinterpret_cast<float*>(clip + i);
    _mm256_storeu_ps(out + 0, _mm256_permute2f128_ps(v01, v11, 0x20));
    _mm256_storeu_ps(out + 8, _mm256_permute2f128_ps(v22, v33, 0x20));
    _mm256_storeu_ps(out + 16, _mm256_permute2f128_ps(v01, v11, 0x31));
    _mm256_storeu_ps(out + 24, _mm256_permute2f128_ps(v22, v33, 0x31));
  }
  transform_vertices_scalar(m, pos + full, n - full, guard_x, guard_y, clip + full, code + full);
}

}  // namespace vertex_transform_avx2
}  // namespace shadowlab
#endif
