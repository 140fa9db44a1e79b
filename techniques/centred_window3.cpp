#include "techniques/centred_window3.h"

#include <cstddef>

namespace shadowlab {

#if defined(__x86_64__)
// The vector rows (techniques/centred_window3_avx2.cpp, centred_window3_avx512.cpp).
namespace centred_window3_avx2 {
void row(const float* r0, const float* r1, const float* r2, int n, float* mean, float* var,
         int stride);
}
namespace centred_window3_avx512 {
void row(const float* r0, const float* r1, const float* r2, int n, float* mean, float* var,
         int stride);
}
#endif

namespace {

// 1/3 and 1/9 rounded to float: the kernels multiply by them (a product per lane is cheaper
// than a division, and every kernel uses the same constants, so the same bits).
constexpr float kThird = 1.0f / 3.0f;
constexpr float kNinth = 1.0f / 9.0f;

// Texel x of a row: the header's sums, in window order, then the mean and the positive part of
// the variance (a NaN gives +0, as v > 0 is false for it).
inline void window_texel(const float* r0, const float* r1, const float* r2, int x, float& mean,
                         float& var) {
  const float c = r1[x + 1];
  float s1 = 0.0f, s2 = 0.0f;
  for (const float* r : {r0, r1, r2})
    for (int i = 0; i < 3; ++i) {
      const float d = r[x + i] - c;
      s1 += d;
      const float u = d * kThird;
      s2 += u * u;
    }
  const float m = s1 * kNinth;
  mean = c + m;
  const float v = s2 - m * m;
  var = v > 0.0f ? v : 0.0f;
}

void row_scalar(const float* r0, const float* r1, const float* r2, int n, float* mean,
                float* var, int stride) {
  centred_window3_scalar_span(r0, r1, r2, 0, n, mean, var, stride);
}

constexpr CentredWindow3Kernels kWindowScalar{Isa::scalar, row_scalar};
#if defined(__x86_64__)
constexpr CentredWindow3Kernels kWindowAvx2{Isa::avx2, centred_window3_avx2::row};
constexpr CentredWindow3Kernels kWindowAvx512{Isa::avx512, centred_window3_avx512::row};
#endif

}  // namespace

void centred_window3_scalar_span(const float* r0, const float* r1, const float* r2, int from,
                                 int n, float* mean, float* var, int stride) {
  for (int x = from; x < n; ++x)
    window_texel(r0, r1, r2, x, mean[size_t(stride) * size_t(x)], var[size_t(stride) * size_t(x)]);
}

const CentredWindow3Kernels& centred_window3_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kWindowAvx512;
  if (isa == Isa::avx2) return kWindowAvx2;
#endif
  (void)isa;
  return kWindowScalar;
}

}  // namespace shadowlab
