#pragma once
// Force-included first in every file of the emulated build (-DSHADOWLAB_EMULATE_SIMD=ON,
// docs/testing.md): the compiler's own intrinsics header, then SIMDe's AVX-512 header
// (Debian's libsimde-dev, which brings AVX2 and everything below it) with its native aliases,
// so `_mm256_*` and `_mm512_*` and their types name SIMDe's portable implementations of
// the same operations wherever the build does not enable the extension itself.
// x86intrin.h rather than immintrin.h: it also brings the AMD extensions' headers, which
// OpenEXR's Imath includes later and which cannot be parsed once the aliases exist.
#include <x86intrin.h>
#define SIMDE_ENABLE_NATIVE_ALIASES
#include <simde/x86/avx512.h>

// SIMDe 0.7.4's portable _mm_testz_si128 returns 1 when either 64-bit half of a & b is zero,
// not only when both are (and its 256-bit form is built on it): the whole AND must be zero.
static inline int shadowlab_emulated_testz_si256(simde__m256i a, simde__m256i b) {
  uint64_t x[4], y[4], any = 0;
  simde_mm256_storeu_si256(x, a);
  simde_mm256_storeu_si256(y, b);
  for (int i = 0; i < 4; ++i) any |= x[i] & y[i];
  return any == 0;
}
#undef _mm256_testz_si256
#define _mm256_testz_si256(a, b) shadowlab_emulated_testz_si256((a), (b))

// The intrinsics SIMDe 0.7 does not provide, by the operations that give the same values: a
// streaming store differs from a plain one only in what it leaves in the caches.
#undef _mm512_stream_ps
#define _mm512_stream_ps(p, v) simde_mm512_storeu_ps((p), (v))
// 8 floats widened to doubles (exact), lane by lane.
static inline simde__m512d shadowlab_emulated_cvtps_pd(simde__m256 a) {
  float f[8];
  double d[8];
  simde_mm256_storeu_ps(f, a);
  for (int i = 0; i < 8; ++i) d[i] = double(f[i]);
  return simde_mm512_loadu_pd(d);
}
#undef _mm512_cvtps_pd
#define _mm512_cvtps_pd(a) shadowlab_emulated_cvtps_pd(a)
// Sign extension of 8 int32 lanes to int64 (core/exp_log.h's exp_wide16), lane by lane.
static inline simde__m512i shadowlab_emulated_cvtepi32_epi64(simde__m256i a) {
  int32_t x[8];
  long long y[8];
  simde_mm256_storeu_si256(x, a);
  for (int i = 0; i < 8; ++i) y[i] = x[i];
  return simde_mm512_loadu_si512(y);
}
#undef _mm512_cvtepi32_epi64
#define _mm512_cvtepi32_epi64(a) shadowlab_emulated_cvtepi32_epi64(a)
#undef _mm512_maskz_cvtepi32_epi64
#define _mm512_maskz_cvtepi32_epi64(k, a) \
  simde_mm512_maskz_mov_epi64((k), shadowlab_emulated_cvtepi32_epi64(a))
// AVX-512DQ's conversion of 8 doubles to int64 in the current rounding mode (nearest-even by
// default): cvtsd2si per lane (__builtin_llrint), which like the vector form gives
// 0x8000000000000000 for NaN and out-of-range values.
static inline simde__m512i shadowlab_emulated_cvtpd_epi64(simde__m512d a) {
  double d[8];
  long long q[8];
  simde_mm512_storeu_pd(d, a);
  for (int i = 0; i < 8; ++i) q[i] = __builtin_llrint(d[i]);
  return simde_mm512_loadu_si512(q);
}
#undef _mm512_maskz_cvtpd_epi64
#define _mm512_maskz_cvtpd_epi64(k, a) simde_mm512_maskz_mov_epi64((k), shadowlab_emulated_cvtpd_epi64(a))
// 8 doubles rounded to floats (nearest-even), the lanes whose mask bit is clear zero.
static inline simde__m256 shadowlab_emulated_maskz_cvtpd_ps(simde__mmask8 k, simde__m512d a) {
  double d[8];
  float f[8];
  simde_mm512_storeu_pd(d, a);
  for (int i = 0; i < 8; ++i) f[i] = ((k >> i) & 1) ? float(d[i]) : 0.0f;
  return simde_mm256_loadu_ps(f);
}
#undef _mm512_maskz_cvtpd_ps
#define _mm512_maskz_cvtpd_ps(k, a) shadowlab_emulated_maskz_cvtpd_ps((k), (a))
// The arithmetic right shift of 8 int64 lanes (counts above 63 fill with the sign), masked.
static inline simde__m512i shadowlab_emulated_maskz_srai_epi64(simde__mmask8 k, simde__m512i a,
                                                               unsigned n) {
  long long q[8];
  simde_mm512_storeu_si512(q, a);
  for (int i = 0; i < 8; ++i) q[i] = ((k >> i) & 1) ? (q[i] >> (n > 63 ? 63 : n)) : 0;
  return simde_mm512_loadu_si512(q);
}
// AVX-512VL's masked 8-lane float load, store and compare. The load and store touch only the
// lanes whose mask bit is set, as the instructions do (they are used where the other lanes'
// addresses may lie outside the buffer).
static inline simde__m256 shadowlab_emulated_maskz_loadu_ps(simde__mmask8 k, const void* p) {
  float f[8];
  for (int i = 0; i < 8; ++i) {
    f[i] = 0.0f;
    if ((k >> i) & 1) __builtin_memcpy(&f[i], static_cast<const char*>(p) + 4 * i, 4);
  }
  return simde_mm256_loadu_ps(f);
}
static inline void shadowlab_emulated_mask_storeu_ps(void* p, simde__mmask8 k, simde__m256 v) {
  float f[8];
  simde_mm256_storeu_ps(f, v);
  for (int i = 0; i < 8; ++i)
    if ((k >> i) & 1) __builtin_memcpy(static_cast<char*>(p) + 4 * i, &f[i], 4);
}
#undef _mm256_maskz_loadu_ps
#define _mm256_maskz_loadu_ps(k, p) shadowlab_emulated_maskz_loadu_ps((k), (p))
#undef _mm256_mask_storeu_ps
#define _mm256_mask_storeu_ps(p, k, v) shadowlab_emulated_mask_storeu_ps((p), (k), (v))
#undef _mm256_mask_cmp_ps_mask
#define _mm256_mask_cmp_ps_mask(k, a, b, imm) \
  static_cast<simde__mmask8>((k) & simde_mm256_cmp_ps_mask((a), (b), (imm)))
#undef _mm512_cmpneq_epi32_mask
#define _mm512_cmpneq_epi32_mask(a, b) \
  static_cast<simde__mmask16>(~simde_mm512_cmpeq_epi32_mask((a), (b)))
// valignd: the 32 lanes of a (high) and b (low) shifted down by n lanes, the low 16 kept, masked.
static inline simde__m512i shadowlab_emulated_maskz_alignr_epi32(simde__mmask16 k, simde__m512i a,
                                                                 simde__m512i b, int n) {
  int32_t both[32], out[16];
  simde_mm512_storeu_si512(both, b);
  simde_mm512_storeu_si512(both + 16, a);
  for (int i = 0; i < 16; ++i) out[i] = ((k >> i) & 1) ? both[(i + (n & 15)) & 31] : 0;
  return simde_mm512_loadu_si512(out);
}
#undef _mm512_maskz_alignr_epi32
#define _mm512_maskz_alignr_epi32(k, a, b, n) shadowlab_emulated_maskz_alignr_epi32((k), (a), (b), (n))
// vpmovdb (each int32 lane truncated to its low byte) and vcvtdq2ps (int32 to float, rounded
// to nearest-even), zero-masked.
static inline simde__m128i shadowlab_emulated_maskz_cvtepi32_epi8(simde__mmask16 k, simde__m512i a) {
  int32_t v[16];
  int8_t out[16];
  simde_mm512_storeu_si512(v, a);
  for (int i = 0; i < 16; ++i) out[i] = ((k >> i) & 1) ? static_cast<int8_t>(v[i] & 0xFF) : 0;
  return simde_mm_loadu_si128(out);
}
static inline simde__m512 shadowlab_emulated_maskz_cvtepi32_ps(simde__mmask16 k, simde__m512i a) {
  int32_t v[16];
  float out[16];
  simde_mm512_storeu_si512(v, a);
  for (int i = 0; i < 16; ++i) out[i] = ((k >> i) & 1) ? static_cast<float>(v[i]) : 0.0f;
  return simde_mm512_loadu_ps(out);
}
#undef _mm512_maskz_cvtepi32_epi8
#define _mm512_maskz_cvtepi32_epi8(k, a) shadowlab_emulated_maskz_cvtepi32_epi8((k), (a))
#undef _mm512_maskz_cvtepi32_ps
#define _mm512_maskz_cvtepi32_ps(k, a) shadowlab_emulated_maskz_cvtepi32_ps((k), (a))
// Masked 16-lane stores, lane by lane (only the selected lanes are touched).
static inline void shadowlab_emulated_mask_storeu_32(void* p, simde__mmask16 k, const void* lanes) {
  for (int i = 0; i < 16; ++i)
    if ((k >> i) & 1)
      __builtin_memcpy(static_cast<char*>(p) + 4 * i, static_cast<const char*>(lanes) + 4 * i, 4);
}
static inline void shadowlab_emulated_mask_storeu_ps(void* p, simde__mmask16 k, simde__m512 v) {
  float f[16];
  simde_mm512_storeu_ps(f, v);
  shadowlab_emulated_mask_storeu_32(p, k, f);
}
static inline void shadowlab_emulated_mask_storeu_epi32(void* p, simde__mmask16 k, simde__m512i v) {
  int32_t q[16];
  simde_mm512_storeu_si512(q, v);
  shadowlab_emulated_mask_storeu_32(p, k, q);
}
#undef _mm512_mask_storeu_ps
#define _mm512_mask_storeu_ps(p, k, v) shadowlab_emulated_mask_storeu_ps((p), (k), (v))
#undef _mm512_mask_storeu_epi32
#define _mm512_mask_storeu_epi32(p, k, v) shadowlab_emulated_mask_storeu_epi32((p), (k), (v))
// Signed int64 compare, and int64 to double (rounded to nearest-even), lane by lane.
static inline simde__mmask8 shadowlab_emulated_cmplt_epi64_mask(simde__m512i a, simde__m512i b) {
  long long x[8], y[8];
  simde_mm512_storeu_si512(x, a);
  simde_mm512_storeu_si512(y, b);
  unsigned m = 0;
  for (int i = 0; i < 8; ++i) m |= unsigned(x[i] < y[i]) << i;
  return static_cast<simde__mmask8>(m);
}
static inline simde__m512d shadowlab_emulated_maskz_cvtepi64_pd(simde__mmask8 k, simde__m512i a) {
  long long x[8];
  double d[8];
  simde_mm512_storeu_si512(x, a);
  for (int i = 0; i < 8; ++i) d[i] = ((k >> i) & 1) ? static_cast<double>(x[i]) : 0.0;
  return simde_mm512_loadu_pd(d);
}
#undef _mm512_cmplt_epi64_mask
#define _mm512_cmplt_epi64_mask(a, b) shadowlab_emulated_cmplt_epi64_mask((a), (b))
#undef _mm512_maskz_cvtepi64_pd
#define _mm512_maskz_cvtepi64_pd(k, a) shadowlab_emulated_maskz_cvtepi64_pd((k), (a))
#undef _mm512_maskz_sqrt_pd
#define _mm512_maskz_sqrt_pd(k, a) simde_mm512_maskz_mov_pd((k), simde_mm512_sqrt_pd(a))
#undef _mm512_maskz_shuffle_ps
#define _mm512_maskz_shuffle_ps(k, a, b, imm) \
  simde_mm512_maskz_mov_ps((k), simde_mm512_shuffle_ps((a), (b), (imm)))
#undef _mm512_maskz_shuffle_f32x4
#define _mm512_maskz_shuffle_f32x4(k, a, b, imm) \
  simde_mm512_maskz_mov_ps((k), simde_mm512_shuffle_f32x4((a), (b), (imm)))
// getexp and getmant of 8 finite nonzero doubles, zero-masked: x = m·2^e with the [1, 2)
// mantissa m and its exponent e, by frexp; getmant here only in the [0.75, 1.5) interval with
// the source's sign (core/exp_log.h's log_wide_m8), m halved from 1.5 on.
static inline simde__m512d shadowlab_emulated_maskz_getexp_pd(simde__mmask8 k, simde__m512d a) {
  double d[8];
  simde_mm512_storeu_pd(d, a);
  for (int i = 0; i < 8; ++i) {
    int e = 0;
    (void)__builtin_frexp(d[i], &e);
    d[i] = ((k >> i) & 1) ? double(e - 1) : 0.0;
  }
  return simde_mm512_loadu_pd(d);
}
static inline simde__m512d shadowlab_emulated_maskz_getmant_p75_pd(simde__mmask8 k, simde__m512d a) {
  double d[8];
  simde_mm512_storeu_pd(d, a);
  for (int i = 0; i < 8; ++i) {
    int e = 0;
    double m = 2.0 * __builtin_fabs(__builtin_frexp(d[i], &e));
    if (m >= 1.5) m *= 0.5;
    d[i] = ((k >> i) & 1) ? __builtin_copysign(m, d[i]) : 0.0;
  }
  return simde_mm512_loadu_pd(d);
}
#undef _mm512_maskz_getexp_pd
#define _mm512_maskz_getexp_pd(k, a) shadowlab_emulated_maskz_getexp_pd((k), (a))
#undef _mm512_maskz_getmant_pd
#define _mm512_maskz_getmant_pd(k, a, interval, sign) \
  shadowlab_emulated_maskz_getmant_p75_pd((k), (a))
// Zero-masked forms: the unmasked operation, then the mask.
#undef _mm512_maskz_cvtps_pd
#define _mm512_maskz_cvtps_pd(k, a) simde_mm512_maskz_mov_pd((k), shadowlab_emulated_cvtps_pd(a))
#undef _mm512_maskz_srai_epi64
#define _mm512_maskz_srai_epi64(k, a, n) shadowlab_emulated_maskz_srai_epi64((k), (a), (n))
#undef _mm512_maskz_slli_epi32
#define _mm512_maskz_slli_epi32(k, a, n) simde_mm512_maskz_mov_epi32((k), simde_mm512_slli_epi32((a), (n)))
#undef _mm512_maskz_slli_epi64
#define _mm512_maskz_slli_epi64(k, a, n) simde_mm512_maskz_mov_epi64((k), simde_mm512_slli_epi64((a), (n)))
#undef _mm512_maskz_srli_epi64
#define _mm512_maskz_srli_epi64(k, a, n) simde_mm512_maskz_mov_epi64((k), simde_mm512_srli_epi64((a), (n)))
// AVX-512VL's masked store of 8 int32 lanes: the lanes whose mask bit is set, one by one.
#undef _mm256_mask_storeu_epi32
#define _mm256_mask_storeu_epi32(p, k, v) shadowlab_emulated_mask_storeu_epi32((p), (k), (v))
static inline void shadowlab_emulated_mask_storeu_epi32(void* p, simde__mmask8 k, simde__m256i v) {
  int32_t lanes[8];
  simde_mm256_storeu_si256(lanes, v);
  for (int i = 0; i < 8; ++i)
    if ((k >> i) & 1) __builtin_memcpy(static_cast<char*>(p) + 4 * i, &lanes[i], 4);
}
// 32-bit logical right shift, zero-masked (core/exp_log.h's log_split_f16), as the others.
#undef _mm512_maskz_srli_epi32
#define _mm512_maskz_srli_epi32(k, a, n) simde_mm512_maskz_mov_epi32((k), simde_mm512_srli_epi32((a), (n)))
// Zero-masked 16-lane float load (the MSM filter's partial steps): only the selected lanes are
// read, as the instruction reads nothing under a clear mask bit; the others are zero.
static inline simde__m512 shadowlab_emulated_maskz_loadu_ps(simde__mmask16 k, const void* p) {
  float f[16] = {};
  for (int i = 0; i < 16; ++i)
    if ((k >> i) & 1) __builtin_memcpy(&f[i], static_cast<const char*>(p) + 4 * i, 4);
  return simde_mm512_loadu_ps(f);
}
#undef _mm512_maskz_loadu_ps
#define _mm512_maskz_loadu_ps(k, p) shadowlab_emulated_maskz_loadu_ps((k), (p))
