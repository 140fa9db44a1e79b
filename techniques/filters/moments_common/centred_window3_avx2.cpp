// The AVX2 row of techniques/filters/moments_common/centred_window3.h: the lanes of core/lanes_avx2.h, the interleave
// below, the body of centred_window3_simd.inl. Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <cstddef>
#include <cstdint>

#include "core/lanes_avx2.h"
#include "techniques/filters/moments_common/centred_window3.h"

namespace shadowlab::centred_window3_avx2 {

using namespace lanes_avx2;

// 8 texels' (mean, variance) pairs in texel order: the unpacks give texels 0 1 | 4 5 and
// 2 3 | 6 7 per 128-bit half, the permutes put the halves in order.
inline void store_zip(float* out, Vf m, Vf v) {
  const __m256 lo = _mm256_unpacklo_ps(m, v);
  const __m256 hi = _mm256_unpackhi_ps(m, v);
  _mm256_storeu_ps(out, _mm256_permute2f128_ps(lo, hi, 0x20));
  _mm256_storeu_ps(out + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
}

#include "techniques/filters/moments_common/centred_window3_simd.inl"

}  // namespace shadowlab::centred_window3_avx2
#endif
