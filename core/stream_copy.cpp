#include "core/stream_copy.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace shadowlab {

#if defined(__x86_64__)
// The vector copies (core/stream_copy_avx2.cpp, stream_copy_avx512.cpp).
namespace stream_copy_avx2 {
void copy(const float* src, size_t n, float* dst);
}
namespace stream_copy_avx512 {
void copy(const float* src, size_t n, float* dst);
}
#endif

namespace {

void stream_copy_scalar(const float* src, size_t n, float* dst) {
  if (n > 0) std::memcpy(dst, src, n * sizeof(float));
}

constexpr StreamCopyKernels kStreamCopyScalar{Isa::scalar, stream_copy_scalar};
#if defined(__x86_64__)
constexpr StreamCopyKernels kStreamCopyAvx2{Isa::avx2, stream_copy_avx2::copy};
constexpr StreamCopyKernels kStreamCopyAvx512{Isa::avx512, stream_copy_avx512::copy};
#endif

}  // namespace

const StreamCopyKernels& stream_copy_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kStreamCopyAvx512;
  if (isa == Isa::avx2) return kStreamCopyAvx2;
#endif
  (void)isa;
  return kStreamCopyScalar;
}

StreamCopy stream_copy_kernel() { return stream_copy_kernels(process_isa()).copy; }

void stream_fence() {
#if defined(__x86_64__)
  _mm_sfence();
#endif
}

}  // namespace shadowlab
