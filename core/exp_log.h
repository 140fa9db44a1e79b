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

// ln x for finite x >= 2^-1000 (the ESM filter's arguments lie in [1, e^700]).
inline double log_d(double x) {
  // x = m·2^e with m in [√½, √2): take the exponent field, then move m above √2 down an octave.
  // Unsigned shifts and a shifter for the int → double conversion: AVX2 has neither a 64-bit
  // arithmetic shift nor a 64-bit integer conversion, and either would keep the loop scalar.
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  const double m0 = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL);
  const uint64_t big = m0 > 1.4142135623730951 ? 1 : 0;
  const double m = std::bit_cast<double>(std::bit_cast<uint64_t>(m0) - (big << 52));
  // e = biased exponent + big − 1023, exactly: (2^52 + n) − (2^52 + 1023) for n < 2^52.
  const uint64_t n = (bits >> 52) + big;
  const double e = std::bit_cast<double>(0x4330000000000000ULL | n) - (4503599627370496.0 + 1023.0);
  // ln m = 2·atanh(s), s = (m − 1)/(m + 1), |s| <= 0.1716: the odd series to s^23.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double q = 1.0 / 23.0;
  q = q * s2 + 1.0 / 21.0;
  q = q * s2 + 1.0 / 19.0;
  q = q * s2 + 1.0 / 17.0;
  q = q * s2 + 1.0 / 15.0;
  q = q * s2 + 1.0 / 13.0;
  q = q * s2 + 1.0 / 11.0;
  q = q * s2 + 1.0 / 9.0;
  q = q * s2 + 1.0 / 7.0;
  q = q * s2 + 1.0 / 5.0;
  q = q * s2 + 1.0 / 3.0;
  const double ln_m = 2.0 * s + 2.0 * s * (s2 * q);
  constexpr double kLn2Hi = 0.693147180369123816490;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  return e * kLn2Hi + (e * kLn2Lo + ln_m);
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
__attribute__((target("avx2"))) inline __m256d exp_d4(__m256d x) {
  const __m256d shifter = _mm256_set1_pd(6755399441055744.0);
  const __m256d t = _mm256_add_pd(_mm256_mul_pd(x, _mm256_set1_pd(23.083120654223414)), shifter);
  const __m256d n = _mm256_sub_pd(t, shifter);
  const __m256d r = _mm256_sub_pd(_mm256_sub_pd(x, _mm256_mul_pd(n, _mm256_set1_pd(0.04332169877307024))),
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

__attribute__((target("avx512f"))) inline __m512d exp_d8(__m512d x) {
  const __m512d shifter = _mm512_set1_pd(6755399441055744.0);
  const __m512d t = _mm512_add_pd(_mm512_mul_pd(x, _mm512_set1_pd(23.083120654223414)), shifter);
  const __m512d n = _mm512_sub_pd(t, shifter);
  const __m512d r = _mm512_sub_pd(_mm512_sub_pd(x, _mm512_mul_pd(n, _mm512_set1_pd(0.04332169877307024))),
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
#endif

}  // namespace shadowlab
