// The AVX-512 table of techniques/lookup/lookup_batches.h: MSM's reconstruction in 8 lanes of doubles,
// the other kernels the AVX2 table's (their time is the gathers'). Compiled with -mavx512f
// -mavx512vl -mavx512dq -mavx512bw (docs/simd.md). The zero-masked conversions with every lane
// on stand for the unmasked ones, whose undefined source GCC 12's -Wmaybe-uninitialized reports
// (the same instruction).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "techniques/lookup/lookup_batches.h"
#include "techniques/filters/msm/moment_bound.h"

namespace shadowlab {
// The AVX2 table's kernels (techniques/lookup/lookup_batches_avx2.cpp).
namespace lookup_batches_avx2 {
void esm_combine8(const float (*z)[8], const float* fx, const float* fy, const float* ct,
                  float* out);
void vsm_batch(const VsmLookupConsts& k, const float (*v)[4][8], const float* fx, const float* fy,
               const float* depth, const int32_t* active, float* out);
void evsm_batch(const EvsmLookupConsts& k, const float (*v)[4][8], const float* fx,
                const float* fy, const float* depth, float* out);
template <int N>
void msm_mixed(const MsmLookupConsts& k, const double (*const* mixed)[8],
               const float* const* depth, float* const* out);
void poisson_batch(const MapLookupConsts& c, const Receivers8& r, const float* cosv,
                   const float* sinv, const vec2* points, int n, float radius, float* out);
void pcss_search(const MapLookupConsts& mc, const Receivers8& r, const float* rs, const float* cs,
                 const float* sn, const float* gxv, const float* gyv, const int32_t* active,
                 const vec2* points, int n, double* sums, int32_t* counts, float* outside_out);
void pcss_pcf(const MapLookupConsts& mc, const Receivers8& r, const float* radius,
              const float* cs, const float* sn, const float* gxv, const float* gyv,
              const int32_t* active, const int32_t* live_lanes, const vec2* points, int n,
              float* vis, float* outside_out);
}  // namespace lookup_batches_avx2
}  // namespace shadowlab

namespace shadowlab::lookup_batches_avx512 {

#include "techniques/filters/msm/moment_bound_avx512.inl"

// bilinear_weights (techniques/filters/moments_common/chebyshev.h) for 8 lanes in double.
[[gnu::always_inline]] inline void bilinear_weights8(__m512d fx, __m512d fy, __m512d w[4]) {
  const __m512d one = _mm512_set1_pd(1.0);
  const __m512d ox = _mm512_sub_pd(one, fx), oy = _mm512_sub_pd(one, fy);
  w[0] = _mm512_mul_pd(ox, oy);
  w[1] = _mm512_mul_pd(fx, oy);
  w[2] = _mm512_mul_pd(ox, fy);
  w[3] = _mm512_mul_pd(fx, fy);
}

// 8 floats widened to doubles.
[[gnu::always_inline]] inline __m512d widen8(const float* p) {
  return _mm512_maskz_cvtps_pd(0xFF, _mm256_loadu_ps(p));
}

// msm_value (moment_shadow_map.cpp) on N batches of 8 lanes at once from their taps: the
// bilinear mix, the 16-bit store's decode, the reconstruction (msm_intensity8n: N > 1 overlaps
// the batches' chains of divisions), each in the scalar order.
template <int N>
void msm_taps(const MsmLookupConsts& k, const float (*const* v)[4][8], const float* const* fx,
              const float* const* fy, const float* const* depth, float* const* out) {
  const __m512d one = _mm512_set1_pd(1.0);
  __m512d m[N][4], z[N], g[N];
  for (int h = 0; h < N; ++h) {
    __m512d w[4];
    bilinear_weights8(widen8(fx[h]), widen8(fy[h]), w);
    for (int j = 0; j < 4; ++j) {
      m[h][j] = _mm512_setzero_pd();
      for (int i = 0; i < 4; ++i)
        m[h][j] = _mm512_add_pd(m[h][j], _mm512_mul_pd(w[i], widen8(v[h][j][i])));
    }
    if (k.quantize16) {
      const __m512d q[4] = {_mm512_sub_pd(m[h][0], _mm512_set1_pd(kMsmOffset)), m[h][1], m[h][2],
                            m[h][3]};
      for (int j = 0; j < 4; ++j) {
        __m512d s = _mm512_mul_pd(q[0], _mm512_set1_pd(kMsmInverse[0][j]));
        for (int i = 1; i < 4; ++i)
          s = _mm512_add_pd(s, _mm512_mul_pd(q[i], _mm512_set1_pd(kMsmInverse[i][j])));
        m[h][j] = s;
      }
    }
    z[h] = widen8(depth[h]);
  }
  msm_intensity8n<N>(m, z, k.alpha, k.hausdorff, g);
  for (int h = 0; h < N; ++h)
    _mm256_storeu_ps(out[h], _mm512_maskz_cvtpd_ps(0xFF, _mm512_sub_pd(one, g[h])));
}

// msm_intensity8n on G groups of 8 lanes (m[i][8h + lane]).
template <int G>
void msm_intensity_lanes(const double (*m)[32], const double* z, double alpha, bool hausdorff,
                         double* out) {
  __m512d mv[G][4], zv[G], g[G];
  for (int h = 0; h < G; ++h) {
    for (int i = 0; i < 4; ++i) mv[h][i] = _mm512_loadu_pd(m[i] + 8 * h);
    zv[h] = _mm512_loadu_pd(z + 8 * h);
  }
  msm_intensity8n<G>(mv, zv, alpha, hausdorff, g);
  for (int h = 0; h < G; ++h) _mm512_storeu_pd(out + 8 * h, g[h]);
}

}  // namespace shadowlab::lookup_batches_avx512

namespace shadowlab {
extern constinit const LookupBatchKernels kLookupBatchesAvx512{
    Isa::avx512,
    lookup_batches_avx2::esm_combine8,
    lookup_batches_avx2::vsm_batch,
    lookup_batches_avx2::evsm_batch,
    lookup_batches_avx2::msm_mixed<1>,
    lookup_batches_avx2::msm_mixed<2>,
    lookup_batches_avx512::msm_taps<1>,
    lookup_batches_avx512::msm_taps<4>,
    lookup_batches_avx512::msm_intensity_lanes<1>,
    lookup_batches_avx512::msm_intensity_lanes<4>,
    8,
    32,
    lookup_batches_avx2::poisson_batch,
    lookup_batches_avx2::pcss_search,
    lookup_batches_avx2::pcss_pcf};
}  // namespace shadowlab
#endif
