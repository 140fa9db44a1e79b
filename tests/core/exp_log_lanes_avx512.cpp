// The AVX-512 table of tests/core/exp_log_lanes.h. Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include "core/exp_log_avx512.h"
#include "exp_log_lanes.h"

namespace shadowlab::test::exp_log_lanes_avx512 {

namespace el = shadowlab::exp_log_avx512;

void exp_d16(const double* x, double* y) {
  for (int k = 0; k < 16; k += 8) _mm512_storeu_pd(y + k, el::exp_d8(_mm512_loadu_pd(x + k)));
}
void log_d16(const double* x, double* y) {
  for (int k = 0; k < 16; k += 8) _mm512_storeu_pd(y + k, el::log_d8(_mm512_loadu_pd(x + k)));
}
void exp_f16(const float* x, float* y) { _mm512_storeu_ps(y, el::exp_f16(_mm512_loadu_ps(x))); }
void exp_wide16(const float* x, double* y) {
  __m512d lo, hi;
  el::exp_wide16(_mm512_loadu_ps(x), lo, hi);
  _mm512_storeu_pd(y, lo);
  _mm512_storeu_pd(y + 8, hi);
}
void log_wide16(const double* x, double* y) {
  __m512d lo, hi;
  el::log_wide16(_mm512_loadu_pd(x), _mm512_loadu_pd(x + 8), lo, hi);
  _mm512_storeu_pd(y, lo);
  _mm512_storeu_pd(y + 8, hi);
}
void log_split_f16(const float* x, float* m, int32_t* e) {
  __m512i ev;
  _mm512_storeu_ps(m, el::log_split_f16(_mm512_loadu_ps(x), ev));
  _mm512_storeu_si512(e, ev);
}

#include "exp_log_lanes_loops.inl"

extern const ExpLogLanes kTable{Isa::avx512, exp_d16,       log_d16,  exp_f16,   exp_wide16,
                                log_wide16,  log_split_f16, exp_loop, expf_loop, log_loop};

}  // namespace shadowlab::test::exp_log_lanes_avx512
#endif
