// The AVX-512 copy of core/stream_copy.h: a line as one 64-byte non-temporal store, the body of
// stream_copy_simd.inl. Compiled with -mavx512f -mavx512vl -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace shadowlab::stream_copy_avx512 {

// 16 floats from src to the line at dst.
[[gnu::always_inline]] inline void stream_line(float* dst, const float* src) {
  _mm512_stream_ps(dst, _mm512_loadu_ps(src));
}

#include "core/stream_copy_simd.inl"

}  // namespace shadowlab::stream_copy_avx512
#endif
