// The AVX2 copy of core/stream_copy.h: a line as two 32-byte non-temporal stores, the body of
// stream_copy_simd.inl. Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace shadowlab::stream_copy_avx2 {

// 16 floats from src to the line at dst.
[[gnu::always_inline]] inline void stream_line(float* dst, const float* src) {
  _mm256_stream_ps(dst, _mm256_loadu_ps(src));
  _mm256_stream_ps(dst + 8, _mm256_loadu_ps(src + 8));
}

#include "core/stream_copy_simd.inl"

}  // namespace shadowlab::stream_copy_avx2
#endif
