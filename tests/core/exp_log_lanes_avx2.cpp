// The AVX2 table of tests/core/exp_log_lanes.h. Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include "core/exp_log_avx2.h"
#include "exp_log_lanes.h"

namespace shadowlab::test::exp_log_lanes_avx2 {

namespace el = shadowlab::exp_log_avx2;

void exp_d16(const double* x, double* y) {
  for (int k = 0; k < 16; k += 4) _mm256_storeu_pd(y + k, el::exp_d4(_mm256_loadu_pd(x + k)));
}
void log_d16(const double* x, double* y) {
  for (int k = 0; k < 16; k += 4) _mm256_storeu_pd(y + k, el::log_d4(_mm256_loadu_pd(x + k)));
}
void exp_f16(const float* x, float* y) {
  for (int k = 0; k < 16; k += 8) _mm256_storeu_ps(y + k, el::exp_f8(_mm256_loadu_ps(x + k)));
}
void exp_wide16(const float* x, double* y) {
  for (int k = 0; k < 16; k += 8) {
    __m256d lo, hi;
    el::exp_wide8(_mm256_loadu_ps(x + k), lo, hi);
    _mm256_storeu_pd(y + k, lo);
    _mm256_storeu_pd(y + k + 4, hi);
  }
}
void log_wide16(const double* x, double* y) {
  for (int k = 0; k < 16; k += 8) {
    __m256d lo, hi;
    el::log_wide8(_mm256_loadu_pd(x + k), _mm256_loadu_pd(x + k + 4), lo, hi);
    _mm256_storeu_pd(y + k, lo);
    _mm256_storeu_pd(y + k + 4, hi);
  }
}
void log_split_f16(const float* x, float* m, int32_t* e) {
  for (int k = 0; k < 16; k += 8) {
    __m256i ev;
    _mm256_storeu_ps(m + k, el::log_split_f8(_mm256_loadu_ps(x + k), ev));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(e + k), ev);
  }
}

#include "exp_log_lanes_loops.inl"

extern const ExpLogLanes kTable{Isa::avx2,  exp_d16,       log_d16,  exp_f16,   exp_wide16,
                                log_wide16, log_split_f16, exp_loop, expf_loop, log_loop};

}  // namespace shadowlab::test::exp_log_lanes_avx2
#endif
