#pragma once
// Branch-free exp and log in double, exp in float, and the float-precision pair exp_wide /
// log_wide whose range is double's, for loops the compiler vectorizes and for kernels written
// with intrinsics (the ESM filter runs one exp and one log per texel, its lookup four exps per
// pixel; glibc's scalar calls were most of their time). Only IEEE multiply, add, subtract and
// divide, float <-> double conversions, integer adds and shifts on the bit patterns and (exp_d)
// a 16-entry table read, in a fixed order: a loop of them compiled for AVX2 or AVX-512 gives the
// same bits as the scalar calls, on any x86-64 (no libm, no FMA: the build has
// -ffp-contract=off). Accuracy against long double (tests/core/exp_log_test.cpp): exp_d, log_d
// and exp_f within 2 ulp of the exact value on the ranges below; exp_wide within 3e-7 relative,
// log_wide within 2e-7 absolute.
#include <bit>
#include <cstdint>

#include "core/simd_target.h"

#if defined(__x86_64__)
#include <immintrin.h>

#include <initializer_list>
#endif

namespace shadowlab {

// 2^(j/16), j = 0..15, each the double nearest the exact value (Python's decimal at 50 digits).
inline constexpr double kExp2Sixteenths[16] = {
    1.0,                1.0442737824274138, 1.0905077326652577, 1.1387886347566916,
    1.189207115002721,  1.241857812073484,  1.2968395546510096, 1.3542555469368927,
    1.4142135623730951, 1.4768261459394993, 1.5422108254079407, 1.6104903319492543,
    1.681792830507429,  1.7562521603732995, 1.8340080864093424, 1.9152065613971474};

// e^x for x in [-700, 700] (the ESM filter's arguments lie in [0, 700]).
// x = (16q + j)·ln2/16 + r, |r| <= ln2/32: e^x = 2^q · 2^(j/16) · e^r. The table step makes the
// polynomial 7 terms where e^r over |r| <= ln2/2 needed 13: the ESM and EVSM filters' exps were
// about half of their time (docs/performance.md).
inline double exp_d(double x) {
  // 16q + j by round-to-nearest through the 1.5·2^52 shifter (exact for |16x·log2e| < 2^51);
  // ln2/16 split so that its high part times any |16q + j| < 2^14 is exact.
  constexpr double k16Log2e = 23.083120654223414;  // 16 / ln 2
  constexpr double kShifter = 6755399441055744.0;  // 1.5 · 2^52
  constexpr double kLn2Hi16 = 0.04332169877307024;    // (0x3FE62E42FEE00000) / 16
  constexpr double kLn2Lo16 = 1.1926343307941173e-11;  // (ln 2 − that high part · 16) / 16
  const double t = x * k16Log2e + kShifter;
  const double n = t - kShifter;
  const double r = (x - n * kLn2Hi16) - n * kLn2Lo16;
  // e^r − 1 by its Taylor series to r^7 (|r| <= 0.0217: truncation below 2e-18), Horner.
  double p = 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r;
  // 2^(j/16) · e^r = T + T·(e^r − 1), then × 2^q: add q to the exponent field. ni = 16q + j
  // (the low bits of t's pattern); (ni & ~15) << 48 is q << 52 for either sign of q.
  const int64_t ni = std::bit_cast<int64_t>(t) - std::bit_cast<int64_t>(kShifter);
  const double tj = kExp2Sixteenths[ni & 15];
  const double s = tj + tj * p;
  return std::bit_cast<double>(std::bit_cast<int64_t>(s) + ((ni & ~int64_t(15)) << 48));
}

// ln c_j of log_d's 16 mantissa steps: c_j = 1 + j/16 for j < 8, and (1 + (j + 1)/16)/2 for
// j >= 8 (mantissas from 1.5 up are taken to the next octave, against the step's upper end, so
// that x just below 1 is 2^0·(1 − ε) with c = 1, not 2^-1·1.99…, whose ln −ln2 + 0.69 would
// cancel): the double nearest each value (hi) and the double nearest what it leaves (lo), from
// Python's decimal at 60 digits.
inline constexpr double kLnStepHi[16] = {
    0.0,                  0.06062462181643484,  0.11778303565638346,  0.17185025692665923,
    0.22314355131420976,  0.27193371548364176,  0.3184537311185346,   0.3629054936893685,
    -0.24686007793152578, -0.2076393647782445,  -0.16989903679539747, -0.13353139262452263,
    -0.09844007281325252, -0.06453852113757118, -0.0317486983145803,  0.0};
inline constexpr double kLnStepLo[16] = {
    0.0,                     2.6424025938726934e-18, -1.1971685747593677e-18,
    -6.0224538210113705e-18, -9.091270597324799e-18, 7.83319637697442e-19,
    2.7114779367326236e-17,  -2.1492361455310972e-17, -1.361743371748368e-17,
    -1.2053243216686129e-17, 4.868008764439071e-19,  3.664457663660085e-18,
    4.439009633675136e-18,   6.470486661692933e-18,  -3.0382263084680858e-18,
    0.0};

// ln x for finite x >= 2^-1000 (the ESM filter's arguments lie in [1, e^700]).
// x = 2^e · m, m in [1, 2); j = m's top 4 fraction bits; c = 1 + (j + [j >= 8])/16, within
// 1/16 of m: ln x = e·ln2 + ln c + 2·atanh(s), s = (m − c)/(m + c), |s| < 1/32 (kLnStepHi/Lo
// hold ln c, halved and e + 1 for j >= 8). The table step makes the series 6 terms where s up
// to 0.17 needed 12.
inline double log_d(double x) {
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  const double m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL);
  const uint64_t j = (bits >> 48) & 15;
  const uint64_t up = j >> 3;  // 1 for j >= 8
  // 1 + (j + up)/16 by adding to 1.0's pattern (j + up = 16 carries into the exponent: 2.0).
  const double c = std::bit_cast<double>(0x3FF0000000000000ULL + ((j + up) << 48));
  // e = biased exponent + (j >= 8) − 1023, exactly: (2^52 + n) − (2^52 + 1023) for n < 2^52.
  // Unsigned shifts and a shifter for the int → double conversion: AVX2 has neither a 64-bit
  // arithmetic shift nor a 64-bit integer conversion.
  const uint64_t n = (bits >> 52) + up;
  const double e = std::bit_cast<double>(0x4330000000000000ULL | n) - (4503599627370496.0 + 1023.0);
  const double s = (m - c) / (m + c);
  const double s2 = s * s;
  double q = 1.0 / 11.0;  // 2·atanh(s) = 2s + 2s·(s²/3 + s⁴/5 + … + s^10/11): s^12/13 < 1e-19
  q = q * s2 + 1.0 / 9.0;
  q = q * s2 + 1.0 / 7.0;
  q = q * s2 + 1.0 / 5.0;
  q = q * s2 + 1.0 / 3.0;
  const double ln_m = 2.0 * s + 2.0 * s * (s2 * q);
  constexpr double kLn2Hi = 0.693147180369123816490;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  return (e * kLn2Hi + kLnStepHi[j]) + (ln_m + (e * kLn2Lo + kLnStepLo[j]));
}

// exp_f's steps before the scale: e^x = p · 2^ni with p = e^r in [0.70, 1.42], r = x − ni·ln2.
// kLn2Hi has 9 significant bits, so ni·kLn2Hi is exact for |ni| < 2^15 and x − ni·kLn2Hi is
// exact (Sterbenz): the reduction holds for |x| up to ~22,000, not only float's range.
inline float exp_f_poly(float x, int32_t& ni) {
  constexpr float kLog2e = 1.44269504f;
  constexpr float kShifter = 12582912.0f;  // 1.5 · 2^23
  constexpr float kLn2Hi = 0.693359375f;   // 0x3F318000
  constexpr float kLn2Lo = -2.12194440e-4f;
  const float t = x * kLog2e + kShifter;
  const float n = t - kShifter;
  const float r = (x - n * kLn2Hi) - n * kLn2Lo;
  // e^r to r^7 (|r| <= 0.35: truncation below 6e-9), Horner.
  float p = 1.0f / 5040.0f;
  p = p * r + 1.0f / 720.0f;
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  ni = std::bit_cast<int32_t>(t) - std::bit_cast<int32_t>(kShifter);
  return p;
}

// e^x in float for x in [-87, 88] (the ESM lookup clamps its exponents to [-87, 80]): within
// 2 ulp of the exact value; 8 lanes per AVX2 instruction where double gives 4.
inline float exp_f(float x) {
  int32_t ni;
  const float p = exp_f_poly(x, ni);
  return std::bit_cast<float>(std::bit_cast<int32_t>(p) + (ni << 23));
}

// e^x for float x in [-708, 708] as a double: exp_f's float steps, then p · 2^ni in double, whose
// range holds e^700 (float's ends at e^88.7). Within 2.5 float ulps (3e-7) of e^x
// (tests/core/exp_log_test.cpp). The ESM filter's exponentials (docs/techniques/esm.md): its
// terms e^(c·(d − d_min)) reach e^700, and float precision is what its float map keeps.
inline double exp_wide(float x) {
  int32_t ni;
  const float p = exp_f_poly(x, ni);
  return std::bit_cast<double>(std::bit_cast<int64_t>(double(p)) + (int64_t(ni) << 52));
}

// ln m for float m in [0.75, 1.5): s = (m − 1)/(m + 1) (|s| <= 0.2), 2·atanh(s) to s^9
// (truncation below 4e-9), in float. The mantissa step of log_wide and of the ESM filter's
// float tiles (techniques/filters/esm/esm_float_tiles.cpp).
inline float ln_m_f(float mf) {
  const float s = (mf - 1.0f) / (mf + 1.0f);
  const float s2 = s * s;
  float q = 1.0f / 9.0f;
  q = q * s2 + 1.0f / 7.0f;
  q = q * s2 + 1.0f / 5.0f;
  q = q * s2 + 1.0f / 3.0f;
  const float two_s = s + s;
  return two_s + two_s * (s2 * q);
}

// ln x for positive normal double x to float precision, as a double: within 2e-7 of ln x
// (absolute; tests/core/exp_log_test.cpp). x = 2^e · m exactly, m in [0.75, 1.5) (mantissas
// from 1.5 up taken to the next octave, as log_d does, so that no sum cancels); then ln m in
// float: m rounded to float, s = (m − 1)/(m + 1) (|s| <= 0.2), 2·atanh(s) to s^9 (truncation
// below 4e-9), and e·ln2 + ln m in double. The ESM filter's logarithms (docs/techniques/esm.md):
// its arguments lie in [1, e^700], beyond float's range, and it stores a float.
inline double log_wide(double x) {
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  const uint64_t up = (bits >> 51) & 1;  // mantissa >= 1.5
  const double m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFULL) |
                                         (0x3FF0000000000000ULL - (up << 52)));
  // e exactly, as log_d forms it: (2^52 + n) − (2^52 + 1023).
  const uint64_t n = (bits >> 52) + up;
  const double e = std::bit_cast<double>(0x4330000000000000ULL | n) - (4503599627370496.0 + 1023.0);
  return e * 0.6931471805599453 + double(ln_m_f(float(m)));
}

// log_wide's split of a positive normal float: x = 2^e · m exactly, m in [0.75, 1.5) (mantissas
// from 1.5 up taken to the next octave, so that ln m by ln_m_f never cancels against e·ln2).
// The ESM filter's float tiles (techniques/filters/esm/esm_float_tiles.h) take ln x as e·ln2 + ln_m_f(m).
inline float log_split_f(float x, int32_t& e) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const uint32_t up = (bits >> 22) & 1;  // mantissa >= 1.5
  e = int32_t((bits >> 23) + up) - 127;
  return std::bit_cast<float>((bits & 0x007FFFFFu) | (0x3F800000u - (up << 23)));
}

#if defined(__x86_64__)
// exp_d of 4 and of 8 doubles with AVX2 and AVX-512 intrinsics: exp_d's operations in exp_d's
// order, the table read by a gather (AVX2) or a two-register permute (AVX-512), so each lane
// gets exp_d's bits (tests/core/exp_log_test.cpp), for kernels written with intrinsics.
SL_TARGET("avx2") inline __m256d exp_d4(__m256d x) {
  const __m256d shifter = _mm256_set1_pd(6755399441055744.0);
  const __m256d t = _mm256_add_pd(_mm256_mul_pd(x, _mm256_set1_pd(23.083120654223414)), shifter);
  const __m256d n = _mm256_sub_pd(t, shifter);
  const __m256d r =
      _mm256_sub_pd(_mm256_sub_pd(x, _mm256_mul_pd(n, _mm256_set1_pd(0.04332169877307024))),
                    _mm256_mul_pd(n, _mm256_set1_pd(1.1926343307941173e-11)));
  __m256d p = _mm256_set1_pd(1.0 / 5040.0);
  for (const double c : {1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0, 1.0 / 6.0, 0.5, 1.0})
    p = _mm256_add_pd(_mm256_mul_pd(p, r), _mm256_set1_pd(c));
  p = _mm256_mul_pd(p, r);
  const __m256i ni = _mm256_sub_epi64(_mm256_castpd_si256(t), _mm256_castpd_si256(shifter));
  const __m256i j = _mm256_and_si256(ni, _mm256_set1_epi64x(15));
  const __m256d tj = _mm256_i64gather_pd(kExp2Sixteenths, j, 8);
  const __m256d s = _mm256_add_pd(tj, _mm256_mul_pd(tj, p));
  const __m256i q = _mm256_slli_epi64(_mm256_andnot_si256(_mm256_set1_epi64x(15), ni), 48);
  return _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(s), q));
}

SL_TARGET("avx512f") inline __m512d exp_d8(__m512d x) {
  const __m512d shifter = _mm512_set1_pd(6755399441055744.0);
  const __m512d t = _mm512_add_pd(_mm512_mul_pd(x, _mm512_set1_pd(23.083120654223414)), shifter);
  const __m512d n = _mm512_sub_pd(t, shifter);
  const __m512d r =
      _mm512_sub_pd(_mm512_sub_pd(x, _mm512_mul_pd(n, _mm512_set1_pd(0.04332169877307024))),
                    _mm512_mul_pd(n, _mm512_set1_pd(1.1926343307941173e-11)));
  __m512d p = _mm512_set1_pd(1.0 / 5040.0);
  for (const double c : {1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0, 1.0 / 6.0, 0.5, 1.0})
    p = _mm512_add_pd(_mm512_mul_pd(p, r), _mm512_set1_pd(c));
  p = _mm512_mul_pd(p, r);
  const __m512i ni = _mm512_sub_epi64(_mm512_castpd_si512(t), _mm512_castpd_si512(shifter));
  // The permute reads the low 4 bits of each index: bit 3 picks the register.
  const __m512d tj = _mm512_permutex2var_pd(_mm512_loadu_pd(kExp2Sixteenths), ni,
                                            _mm512_loadu_pd(kExp2Sixteenths + 8));
  const __m512d s = _mm512_add_pd(tj, _mm512_mul_pd(tj, p));
  // The zero-masked forms with every lane on: GCC 12's unmasked ones pass an undefined source
  // that -Wmaybe-uninitialized reports (the same instructions either way).
  const __m512i q16 = _mm512_and_si512(ni, _mm512_set1_epi64(~int64_t(15)));
  const __m512i q = _mm512_maskz_slli_epi64(0xFF, q16, 48);
  return _mm512_castsi512_pd(_mm512_add_epi64(_mm512_castpd_si512(s), q));
}

// exp_f of 8 floats (AVX2) and of 16 (AVX-512): exp_f's operations in exp_f's order, so each
// lane gets exp_f's bits (tests/core/exp_log_test.cpp), for the EVSM filter's rows and the
// ESM lookup's AVX2 batch.
SL_TARGET("avx2") inline __m256 exp_f8_poly(__m256 x, __m256i& ni) {
  const __m256 shifter = _mm256_set1_ps(12582912.0f);
  const __m256 t = _mm256_add_ps(_mm256_mul_ps(x, _mm256_set1_ps(1.44269504f)), shifter);
  const __m256 n = _mm256_sub_ps(t, shifter);
  const __m256 r = _mm256_sub_ps(_mm256_sub_ps(x, _mm256_mul_ps(n, _mm256_set1_ps(0.693359375f))),
                                 _mm256_mul_ps(n, _mm256_set1_ps(-2.12194440e-4f)));
  __m256 p = _mm256_set1_ps(1.0f / 5040.0f);
  for (const float c : {1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f, 1.0f / 6.0f, 0.5f, 1.0f, 1.0f})
    p = _mm256_add_ps(_mm256_mul_ps(p, r), _mm256_set1_ps(c));
  ni = _mm256_sub_epi32(_mm256_castps_si256(t), _mm256_castps_si256(shifter));
  return p;
}

SL_TARGET("avx2") inline __m256 exp_f8(__m256 x) {
  __m256i ni;
  const __m256 p = exp_f8_poly(x, ni);
  return _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(p), _mm256_slli_epi32(ni, 23)));
}

SL_TARGET("avx512f") inline __m512 exp_f16_poly(__m512 x, __m512i& ni) {
  const __m512 shifter = _mm512_set1_ps(12582912.0f);
  const __m512 t = _mm512_add_ps(_mm512_mul_ps(x, _mm512_set1_ps(1.44269504f)), shifter);
  const __m512 n = _mm512_sub_ps(t, shifter);
  const __m512 r = _mm512_sub_ps(_mm512_sub_ps(x, _mm512_mul_ps(n, _mm512_set1_ps(0.693359375f))),
                                 _mm512_mul_ps(n, _mm512_set1_ps(-2.12194440e-4f)));
  __m512 p = _mm512_set1_ps(1.0f / 5040.0f);
  for (const float c : {1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f, 1.0f / 6.0f, 0.5f, 1.0f, 1.0f})
    p = _mm512_add_ps(_mm512_mul_ps(p, r), _mm512_set1_ps(c));
  ni = _mm512_sub_epi32(_mm512_castps_si512(t), _mm512_castps_si512(shifter));
  return p;
}

SL_TARGET("avx512f") inline __m512 exp_f16(__m512 x) {
  __m512i ni;
  const __m512 p = exp_f16_poly(x, ni);
  // The zero-masked shift with every lane on, as in exp_d8.
  const __m512i q = _mm512_maskz_slli_epi32(0xFFFF, ni, 23);
  return _mm512_castsi512_ps(_mm512_add_epi32(_mm512_castps_si512(p), q));
}

// p · 2^n for floats p and int32 n, widened: n shifted into the double's exponent field.
SL_TARGET("avx2") inline __m256d scale_wide4(__m128 p, __m128i n) {
  const __m256i q = _mm256_slli_epi64(_mm256_cvtepi32_epi64(n), 52);
  return _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(_mm256_cvtps_pd(p)), q));
}

// exp_wide of 8 floats (AVX2) and of 16 (AVX-512, below), lanes 0..3 / 0..7 into lo and the
// rest into hi: exp_f's float steps, then p widened and 2^ni added to its exponent in 64-bit
// lanes, so each lane gets exp_wide's bits (tests/core/exp_log_test.cpp).
SL_TARGET("avx2") inline void exp_wide8(__m256 x, __m256d& lo, __m256d& hi) {
  __m256i ni;
  const __m256 p = exp_f8_poly(x, ni);
  lo = scale_wide4(_mm256_castps256_ps128(p), _mm256_castsi256_si128(ni));
  hi = scale_wide4(_mm256_extractf128_ps(p, 1), _mm256_extracti128_si256(ni, 1));
}

// Halves of a 512-bit vector and two halves joined, in the zero-masked forms with every lane on:
// GCC 12's unmasked extracts and inserts (and the casts built on them) pass an undefined source
// that -Wmaybe-uninitialized reports, as in exp_d8.
SL_TARGET("avx512f") inline __m256 half_ps(__m512 v, int hi) {
  return _mm256_castpd_ps(hi ? _mm512_maskz_extractf64x4_pd(0xF, _mm512_castps_pd(v), 1)
                             : _mm512_maskz_extractf64x4_pd(0xF, _mm512_castps_pd(v), 0));
}
SL_TARGET("avx512f") inline __m256i half_si(__m512i v, int hi) {
  return hi ? _mm512_maskz_extracti64x4_epi64(0xF, v, 1)
            : _mm512_maskz_extracti64x4_epi64(0xF, v, 0);
}
SL_TARGET("avx512f") inline __m512 join_ps(__m256 lo, __m256 hi) {
  return _mm512_castpd_ps(_mm512_maskz_insertf64x4(
      0xFF, _mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}

SL_TARGET("avx512f") inline __m512d scale_wide8(__m256 p, __m256i n) {
  const __m512i q = _mm512_maskz_slli_epi64(0xFF, _mm512_maskz_cvtepi32_epi64(0xFF, n), 52);
  return _mm512_castsi512_pd(
      _mm512_add_epi64(_mm512_castpd_si512(_mm512_maskz_cvtps_pd(0xFF, p)), q));
}

SL_TARGET("avx512f") inline void exp_wide16(__m512 x, __m512d& lo, __m512d& hi) {
  __m512i ni;
  const __m512 p = exp_f16_poly(x, ni);
  lo = scale_wide8(half_ps(p, 0), half_si(ni, 0));
  hi = scale_wide8(half_ps(p, 1), half_si(ni, 1));
}

// log_d of 4 and of 8 doubles, as exp_d4 and exp_d8 are to exp_d (tables by gathers, or by
// two-register permutes).
SL_TARGET("avx2") inline __m256d log_d4(__m256d x) {
  const __m256i bits = _mm256_castpd_si256(x);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256i one_bits = _mm256_castpd_si256(one);
  const __m256d m = _mm256_castsi256_pd(
      _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x(0x000FFFFFFFFFFFFFLL)), one_bits));
  const __m256i j = _mm256_and_si256(_mm256_srli_epi64(bits, 48), _mm256_set1_epi64x(15));
  const __m256i up = _mm256_srli_epi64(j, 3);
  const __m256d c = _mm256_castsi256_pd(
      _mm256_add_epi64(one_bits, _mm256_slli_epi64(_mm256_add_epi64(j, up), 48)));
  const __m256i n = _mm256_add_epi64(_mm256_srli_epi64(bits, 52), up);
  const __m256d e = _mm256_sub_pd(
      _mm256_castsi256_pd(_mm256_or_si256(_mm256_set1_epi64x(0x4330000000000000LL), n)),
      _mm256_set1_pd(4503599627370496.0 + 1023.0));
  const __m256d s = _mm256_div_pd(_mm256_sub_pd(m, c), _mm256_add_pd(m, c));
  const __m256d s2 = _mm256_mul_pd(s, s);
  __m256d q = _mm256_set1_pd(1.0 / 11.0);
  for (const double k : {1.0 / 9.0, 1.0 / 7.0, 1.0 / 5.0, 1.0 / 3.0})
    q = _mm256_add_pd(_mm256_mul_pd(q, s2), _mm256_set1_pd(k));
  const __m256d two_s = _mm256_mul_pd(_mm256_set1_pd(2.0), s);
  const __m256d ln_m = _mm256_add_pd(two_s, _mm256_mul_pd(two_s, _mm256_mul_pd(s2, q)));
  const __m256d hi = _mm256_i64gather_pd(kLnStepHi, j, 8);
  const __m256d lo = _mm256_i64gather_pd(kLnStepLo, j, 8);
  const __m256d a = _mm256_add_pd(_mm256_mul_pd(e, _mm256_set1_pd(0.693147180369123816490)), hi);
  const __m256d b = _mm256_add_pd(_mm256_mul_pd(e, _mm256_set1_pd(1.90821492927058770002e-10)), lo);
  return _mm256_add_pd(a, _mm256_add_pd(ln_m, b));
}

SL_TARGET("avx512f") inline __m512d log_d8(__m512d x) {
  const __m512i bits = _mm512_castpd_si512(x);
  const __m512i one_bits = _mm512_set1_epi64(0x3FF0000000000000LL);
  const __m512d m = _mm512_castsi512_pd(
      _mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi64(0x000FFFFFFFFFFFFFLL)), one_bits));
  // Zero-masked shifts with every lane on, as in exp_d8.
  const __m512i j =
      _mm512_and_si512(_mm512_maskz_srli_epi64(0xFF, bits, 48), _mm512_set1_epi64(15));
  const __m512i up = _mm512_maskz_srli_epi64(0xFF, j, 3);
  const __m512d c = _mm512_castsi512_pd(
      _mm512_add_epi64(one_bits, _mm512_maskz_slli_epi64(0xFF, _mm512_add_epi64(j, up), 48)));
  const __m512i n = _mm512_add_epi64(_mm512_maskz_srli_epi64(0xFF, bits, 52), up);
  const __m512d e = _mm512_sub_pd(
      _mm512_castsi512_pd(_mm512_or_si512(_mm512_set1_epi64(0x4330000000000000LL), n)),
      _mm512_set1_pd(4503599627370496.0 + 1023.0));
  const __m512d s = _mm512_div_pd(_mm512_sub_pd(m, c), _mm512_add_pd(m, c));
  const __m512d s2 = _mm512_mul_pd(s, s);
  __m512d q = _mm512_set1_pd(1.0 / 11.0);
  for (const double k : {1.0 / 9.0, 1.0 / 7.0, 1.0 / 5.0, 1.0 / 3.0})
    q = _mm512_add_pd(_mm512_mul_pd(q, s2), _mm512_set1_pd(k));
  const __m512d two_s = _mm512_mul_pd(_mm512_set1_pd(2.0), s);
  const __m512d ln_m = _mm512_add_pd(two_s, _mm512_mul_pd(two_s, _mm512_mul_pd(s2, q)));
  const __m512d hi =
      _mm512_permutex2var_pd(_mm512_loadu_pd(kLnStepHi), j, _mm512_loadu_pd(kLnStepHi + 8));
  const __m512d lo =
      _mm512_permutex2var_pd(_mm512_loadu_pd(kLnStepLo), j, _mm512_loadu_pd(kLnStepLo + 8));
  const __m512d a = _mm512_add_pd(_mm512_mul_pd(e, _mm512_set1_pd(0.693147180369123816490)), hi);
  const __m512d b = _mm512_add_pd(_mm512_mul_pd(e, _mm512_set1_pd(1.90821492927058770002e-10)), lo);
  return _mm512_add_pd(a, _mm512_add_pd(ln_m, b));
}

// log_wide's split of 4 (8, below) doubles: e, and m rounded to float.
SL_TARGET("avx2") inline __m128 log_wide_m4(__m256d x, __m256d& e) {
  const __m256i bits = _mm256_castpd_si256(x);
  const __m256i up = _mm256_and_si256(_mm256_srli_epi64(bits, 51), _mm256_set1_epi64x(1));
  const __m256i m_exp =
      _mm256_sub_epi64(_mm256_set1_epi64x(0x3FF0000000000000LL), _mm256_slli_epi64(up, 52));
  const __m256i mant = _mm256_and_si256(bits, _mm256_set1_epi64x(0x000FFFFFFFFFFFFFLL));
  const __m256d m = _mm256_castsi256_pd(_mm256_or_si256(mant, m_exp));
  const __m256i n = _mm256_add_epi64(_mm256_srli_epi64(bits, 52), up);
  const __m256i e_bits = _mm256_or_si256(_mm256_set1_epi64x(0x4330000000000000LL), n);
  e = _mm256_sub_pd(_mm256_castsi256_pd(e_bits), _mm256_set1_pd(4503599627370496.0 + 1023.0));
  return _mm256_cvtpd_ps(m);
}

// log_wide's ln m of 8 (16, below) floats m.
SL_TARGET("avx2") inline __m256 ln_m8(__m256 mf) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 s = _mm256_div_ps(_mm256_sub_ps(mf, one), _mm256_add_ps(mf, one));
  const __m256 s2 = _mm256_mul_ps(s, s);
  __m256 q = _mm256_set1_ps(1.0f / 9.0f);
  for (const float k : {1.0f / 7.0f, 1.0f / 5.0f, 1.0f / 3.0f})
    q = _mm256_add_ps(_mm256_mul_ps(q, s2), _mm256_set1_ps(k));
  const __m256 two_s = _mm256_add_ps(s, s);
  return _mm256_add_ps(two_s, _mm256_mul_ps(two_s, _mm256_mul_ps(s2, q)));
}

// log_wide of 8 doubles (AVX2: two vectors of 4) and of 16 (AVX-512: two of 8, below), lane for
// lane into lo and hi: log_wide's exact split of each double into e and m, the m's rounded to
// floats and their ln taken 8 or 16 at a time in log_wide's order, then e·ln2 + ln m in double,
// so each lane gets log_wide's bits (tests/core/exp_log_test.cpp).
SL_TARGET("avx2") inline void log_wide8(__m256d x_lo, __m256d x_hi, __m256d& lo, __m256d& hi) {
  __m256d e_lo, e_hi;
  const __m128 m_lo = log_wide_m4(x_lo, e_lo), m_hi = log_wide_m4(x_hi, e_hi);
  const __m256 ln_m = ln_m8(_mm256_set_m128(m_hi, m_lo));
  const __m256d ln2 = _mm256_set1_pd(0.6931471805599453);
  lo = _mm256_add_pd(_mm256_mul_pd(e_lo, ln2), _mm256_cvtps_pd(_mm256_castps256_ps128(ln_m)));
  hi = _mm256_add_pd(_mm256_mul_pd(e_hi, ln2), _mm256_cvtps_pd(_mm256_extractf128_ps(ln_m, 1)));
}

// log_wide's split of 8 positive normal doubles, x = m·2^e with m in [0.75, 1.5): getmant's
// [0.75, 1.5) interval is that m exactly (the [1, 2) mantissa, halved from 1.5 on), getexp the
// exponent of x's [1, 2) form, one more where the mantissa was halved; the two instructions do
// what log_wide's eleven integer steps do, in fewer instructions.
// Returns m as floats; e as doubles (exact integers). The zero-masked forms with every lane on:
// GCC 12's unmasked ones trip -Wmaybe-uninitialized, as in exp_d8.
SL_TARGET("avx512f") inline __m256 log_wide_m8(__m512d x, __m512d& e) {
  const __m512d m = _mm512_maskz_getmant_pd(0xFF, x, _MM_MANT_NORM_p75_1p5, _MM_MANT_SIGN_src);
  const __m512d g = _mm512_maskz_getexp_pd(0xFF, x);
  const __m512d one = _mm512_set1_pd(1.0);
  e = _mm512_mask_add_pd(g, _mm512_cmp_pd_mask(m, one, _CMP_LT_OQ), g, one);
  return _mm512_maskz_cvtpd_ps(0xFF, m);
}

SL_TARGET("avx512f") inline __m512 ln_m16(__m512 mf) {
  const __m512 one = _mm512_set1_ps(1.0f);
  const __m512 s = _mm512_div_ps(_mm512_sub_ps(mf, one), _mm512_add_ps(mf, one));
  const __m512 s2 = _mm512_mul_ps(s, s);
  __m512 q = _mm512_set1_ps(1.0f / 9.0f);
  for (const float k : {1.0f / 7.0f, 1.0f / 5.0f, 1.0f / 3.0f})
    q = _mm512_add_ps(_mm512_mul_ps(q, s2), _mm512_set1_ps(k));
  const __m512 two_s = _mm512_add_ps(s, s);
  return _mm512_add_ps(two_s, _mm512_mul_ps(two_s, _mm512_mul_ps(s2, q)));
}

SL_TARGET("avx512f") inline void log_wide16(__m512d x_lo, __m512d x_hi, __m512d& lo,
                                            __m512d& hi) {
  __m512d e_lo, e_hi;
  const __m256 m_lo = log_wide_m8(x_lo, e_lo), m_hi = log_wide_m8(x_hi, e_hi);
  const __m512 ln_m = ln_m16(join_ps(m_lo, m_hi));
  const __m512d ln2 = _mm512_set1_pd(0.6931471805599453);
  lo = _mm512_add_pd(_mm512_mul_pd(e_lo, ln2), _mm512_maskz_cvtps_pd(0xFF, half_ps(ln_m, 0)));
  hi = _mm512_add_pd(_mm512_mul_pd(e_hi, ln2), _mm512_maskz_cvtps_pd(0xFF, half_ps(ln_m, 1)));
}

// log_split_f of 8 floats (AVX2) and of 16 (AVX-512): the same integer steps in 32-bit lanes,
// so each lane gets log_split_f's m and e (tests/core/exp_log_test.cpp).
SL_TARGET("avx2") inline __m256 log_split_f8(__m256 x, __m256i& e) {
  const __m256i bits = _mm256_castps_si256(x);
  const __m256i up = _mm256_and_si256(_mm256_srli_epi32(bits, 22), _mm256_set1_epi32(1));
  e = _mm256_sub_epi32(_mm256_add_epi32(_mm256_srli_epi32(bits, 23), up), _mm256_set1_epi32(127));
  const __m256i m_exp =
      _mm256_sub_epi32(_mm256_set1_epi32(0x3F800000), _mm256_slli_epi32(up, 23));
  return _mm256_castsi256_ps(
      _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi32(0x007FFFFF)), m_exp));
}

// (The zero-masked shifts with every lane on, as in exp_f16.)
SL_TARGET("avx512f") inline __m512 log_split_f16(__m512 x, __m512i& e) {
  const __m512i bits = _mm512_castps_si512(x);
  const __m512i up =
      _mm512_and_si512(_mm512_maskz_srli_epi32(0xFFFF, bits, 22), _mm512_set1_epi32(1));
  e = _mm512_sub_epi32(_mm512_add_epi32(_mm512_maskz_srli_epi32(0xFFFF, bits, 23), up),
                       _mm512_set1_epi32(127));
  const __m512i m_exp =
      _mm512_sub_epi32(_mm512_set1_epi32(0x3F800000), _mm512_maskz_slli_epi32(0xFFFF, up, 23));
  return _mm512_castsi512_ps(
      _mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi32(0x007FFFFF)), m_exp));
}
#endif

}  // namespace shadowlab
