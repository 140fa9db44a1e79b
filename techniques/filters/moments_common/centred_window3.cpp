#include "techniques/filters/moments_common/centred_window3.h"

#include <cstddef>

namespace shadowlab {

#if defined(__x86_64__)
// The vector rows (techniques/filters/moments_common/centred_window3_avx2.cpp, centred_window3_avx512.cpp).
namespace centred_window3_avx2 {
void row(const float* r0, const float* r1, const float* r2, int n, float* mean, float* var,
         int stride);
}
namespace centred_window3_avx512 {
void row(const float* r0, const float* r1, const float* r2, int n, float* mean, float* var,
         int stride);
}
#endif

namespace centred_window3_scalar {

#include "techniques/filters/moments_common/centred_window3_texel.inl"

}  // namespace centred_window3_scalar

namespace {

void row_scalar(const float* r0, const float* r1, const float* r2, int n, float* mean,
                float* var, int stride) {
  centred_window3_scalar::scalar_span(r0, r1, r2, 0, n, mean, var, stride);
}

constexpr CentredWindow3Kernels kWindowScalar{Isa::scalar, row_scalar};
#if defined(__x86_64__)
constexpr CentredWindow3Kernels kWindowAvx2{Isa::avx2, centred_window3_avx2::row};
constexpr CentredWindow3Kernels kWindowAvx512{Isa::avx512, centred_window3_avx512::row};
#endif

}  // namespace

const CentredWindow3Kernels& centred_window3_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kWindowAvx512;
  if (isa == Isa::avx2) return kWindowAvx2;
#endif
  (void)isa;
  return kWindowScalar;
}

}  // namespace shadowlab
