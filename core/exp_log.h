#pragma once
// Branch-free exp and log in double, and exp in float, for loops the compiler vectorizes (the
// ESM filter runs one exp and one log per texel, its lookup four exps per pixel; glibc's scalar
// calls were most of their time). Only IEEE multiply, add,
// subtract and divide, integer adds and shifts on the bit patterns and (exp_d) a 16-entry table
// read, in a fixed order: a loop of them compiled for AVX2 gives the same bits as the scalar
// calls, on any x86-64 (no libm, no FMA: the build has -ffp-contract=off). Accuracy: within
// 2 ulp of the exact value on the ranges below (tests/core/exp_log_test.cpp checks against long
// double).
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
// about half of their time (README "Technique benchmark").
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

// e^x in float for x in [-87, 88] (the ESM lookup clamps its exponents to [-87, 80]): within
// 2 ulp of the exact value; 8 lanes per AVX2 instruction where double gives 4.
inline float exp_f(float x) {
  constexpr float kLog2e = 1.44269504f;
  constexpr float kShifter = 12582912.0f;  // 1.5 · 2^23
  constexpr float kLn2Hi = 0.693359375f;   // 0x3F318000: n·kLn2Hi exact for |n| < 2^8
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
  const int32_t ni = std::bit_cast<int32_t>(t) - std::bit_cast<int32_t>(kShifter);
  return std::bit_cast<float>(std::bit_cast<int32_t>(p) + (ni << 23));
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
SL_TARGET("avx2") inline __m256 exp_f8(__m256 x) {
  const __m256 shifter = _mm256_set1_ps(12582912.0f);
  const __m256 t = _mm256_add_ps(_mm256_mul_ps(x, _mm256_set1_ps(1.44269504f)), shifter);
  const __m256 n = _mm256_sub_ps(t, shifter);
  const __m256 r = _mm256_sub_ps(_mm256_sub_ps(x, _mm256_mul_ps(n, _mm256_set1_ps(0.693359375f))),
                                 _mm256_mul_ps(n, _mm256_set1_ps(-2.12194440e-4f)));
  __m256 p = _mm256_set1_ps(1.0f / 5040.0f);
  for (const float c : {1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f, 1.0f / 6.0f, 0.5f, 1.0f, 1.0f})
    p = _mm256_add_ps(_mm256_mul_ps(p, r), _mm256_set1_ps(c));
  const __m256i ni = _mm256_sub_epi32(_mm256_castps_si256(t), _mm256_castps_si256(shifter));
  return _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(p), _mm256_slli_epi32(ni, 23)));
}

SL_TARGET("avx512f") inline __m512 exp_f16(__m512 x) {
  const __m512 shifter = _mm512_set1_ps(12582912.0f);
  const __m512 t = _mm512_add_ps(_mm512_mul_ps(x, _mm512_set1_ps(1.44269504f)), shifter);
  const __m512 n = _mm512_sub_ps(t, shifter);
  const __m512 r = _mm512_sub_ps(_mm512_sub_ps(x, _mm512_mul_ps(n, _mm512_set1_ps(0.693359375f))),
                                 _mm512_mul_ps(n, _mm512_set1_ps(-2.12194440e-4f)));
  __m512 p = _mm512_set1_ps(1.0f / 5040.0f);
  for (const float c : {1.0f / 720.0f, 1.0f / 120.0f, 1.0f / 24.0f, 1.0f / 6.0f, 0.5f, 1.0f, 1.0f})
    p = _mm512_add_ps(_mm512_mul_ps(p, r), _mm512_set1_ps(c));
  const __m512i ni = _mm512_sub_epi32(_mm512_castps_si512(t), _mm512_castps_si512(shifter));
  // The zero-masked shift with every lane on, as in exp_d8.
  const __m512i q = _mm512_maskz_slli_epi32(0xFFFF, ni, 23);
  return _mm512_castsi512_ps(_mm512_add_epi32(_mm512_castps_si512(p), q));
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
#endif

}  // namespace shadowlab
