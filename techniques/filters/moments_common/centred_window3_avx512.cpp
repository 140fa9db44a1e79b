// The AVX-512 row of techniques/filters/moments_common/centred_window3.h: the lanes of core/lanes_avx512.h, the
// interleave below, the body of centred_window3_simd.inl. Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <cstddef>
#include <cstdint>

#include "core/lanes_avx512.h"
#include "techniques/filters/moments_common/centred_window3.h"

namespace shadowlab::centred_window3_avx512 {

using namespace lanes_avx512;

// 16 texels' (mean, variance) pairs in texel order. Per 128-bit lane q, t0 holds texels 4q,
// 4q + 1 (mean, variance each) and t1 texels 4q + 2, 4q + 3; the two index vectors take lanes
// 0 1 and 2 3 of both in texel order. The zero-masked unpacks with every lane on: GCC 12's
// unmasked ones trip -Wmaybe-uninitialized (as in core/exp_log.h).
inline void store_zip(float* out, Vf m, Vf v) {
  const __m512i first = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 4, 5, 6, 7, 20, 21, 22, 23);
  const __m512i second =
      _mm512_setr_epi32(8, 9, 10, 11, 24, 25, 26, 27, 12, 13, 14, 15, 28, 29, 30, 31);
  const __m512 t0 = _mm512_maskz_unpacklo_ps(0xFFFF, m, v);
  const __m512 t1 = _mm512_maskz_unpackhi_ps(0xFFFF, m, v);
  _mm512_storeu_ps(out, _mm512_permutex2var_ps(t0, first, t1));
  _mm512_storeu_ps(out + 16, _mm512_permutex2var_ps(t0, second, t1));
}

#include "techniques/filters/moments_common/centred_window3_simd.inl"

}  // namespace shadowlab::centred_window3_avx512
#endif
