#include "core/stream_copy.h"

#include <cstdint>
#include <cstring>

#include "core/isa.h"
#include "core/simd_target.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace shadowlab {

void stream_copy_scalar(const float* src, size_t n, float* dst) {
  if (n > 0) std::memcpy(dst, src, n * sizeof(float));
}

#if defined(__x86_64__)
namespace {

// Floats before dst reaches a 64-byte boundary (dst is 4-byte aligned), at most n.
size_t floats_to_line(const float* dst, size_t n) {
  const size_t bytes = (64 - (reinterpret_cast<uintptr_t>(dst) & 63)) & 63;
  return bytes / 4 < n ? bytes / 4 : n;
}

}  // namespace

// Head and tail (partial lines) by memcpy; the lines between, 16 floats per store.
SL_TARGET("avx512f") void stream_copy_avx512(const float* src, size_t n,
                                             float* dst) {
  const size_t head = floats_to_line(dst, n);
  std::memcpy(dst, src, head * sizeof(float));
  size_t i = head;
  for (; i + 16 <= n; i += 16) _mm512_stream_ps(dst + i, _mm512_loadu_ps(src + i));
  std::memcpy(dst + i, src + i, (n - i) * sizeof(float));
}

// As the AVX-512 copy, a line as two 32-byte stores.
SL_TARGET("avx2") void stream_copy_avx2(const float* src, size_t n, float* dst) {
  const size_t head = floats_to_line(dst, n);
  std::memcpy(dst, src, head * sizeof(float));
  size_t i = head;
  for (; i + 16 <= n; i += 16) {
    _mm256_stream_ps(dst + i, _mm256_loadu_ps(src + i));
    _mm256_stream_ps(dst + i + 8, _mm256_loadu_ps(src + i + 8));
  }
  std::memcpy(dst + i, src + i, (n - i) * sizeof(float));
}
#else
void stream_copy_avx512(const float* src, size_t n, float* dst) { stream_copy_scalar(src, n, dst); }
void stream_copy_avx2(const float* src, size_t n, float* dst) { stream_copy_scalar(src, n, dst); }
#endif

void stream_fence() {
#if defined(__x86_64__)
  _mm_sfence();
#endif
}

StreamCopy stream_copy_kernel() {
  if (process_isa() == Isa::avx512) return stream_copy_avx512;
  if (process_isa() >= Isa::avx2) return stream_copy_avx2;
  return stream_copy_scalar;
}

}  // namespace shadowlab
