#pragma once
// Branch-free exp and log in double, and exp in float, for loops the compiler vectorizes (the
// ESM filter runs one exp and one log per texel, its lookup four exps per pixel; glibc's scalar
// calls were most of their time). Only IEEE multiply, add,
// subtract and divide, integer adds and shifts on the bit patterns, in a fixed order: a loop of
// them compiled for AVX2 gives the same bits as the scalar calls, on any x86-64 (no libm, no
// FMA: the build has -ffp-contract=off). Accuracy: within 2 ulp of the exact value on the
// ranges below (tests/core/exp_log_test.cpp checks against long double).
#include <bit>
#include <cstdint>
#if defined(__x86_64__)
#include <immintrin.h>

#include <initializer_list>
#endif

namespace shadowlab {

// e^x for x in [-700, 700] (the ESM filter's arguments lie in [0, 700]).
inline double exp_d(double x) {
  // x = n·ln2 + r, |r| <= ln2/2: n by round-to-nearest through the 1.5·2^52 shifter (exact for
  // |x·log2e| < 2^51), ln2 split so that n·ln2_hi is exact for |n| < 2^11.
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kShifter = 6755399441055744.0;  // 1.5 · 2^52
  constexpr double kLn2Hi = 0.693147180369123816490;   // 0x3FE62E42FEE00000
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  const double t = x * kLog2e + kShifter;
  const double n = t - kShifter;
  const double r = (x - n * kLn2Hi) - n * kLn2Lo;
  // e^r by its Taylor series to r^13 (|r| <= 0.347: truncation below 1e-17), Horner.
  double p = 1.0 / 6227020800.0;  // 1/13!
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // × 2^n: add n to the exponent field (n is the low bits of t's pattern).
  const int64_t ni = std::bit_cast<int64_t>(t) - std::bit_cast<int64_t>(kShifter);
  return std::bit_cast<double>(std::bit_cast<int64_t>(p) + (ni << 52));
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
// exp_d of 4 doubles with AVX2 intrinsics: exp_d's operations in exp_d's order, so each lane
// gets exp_d's bits (tests/core/exp_log_test.cpp), for kernels written with intrinsics.
__attribute__((target("avx2"))) inline __m256d exp_d4(__m256d x) {
  const __m256d shifter = _mm256_set1_pd(6755399441055744.0);
  const __m256d t = _mm256_add_pd(_mm256_mul_pd(x, _mm256_set1_pd(1.4426950408889634)), shifter);
  const __m256d n = _mm256_sub_pd(t, shifter);
  const __m256d r = _mm256_sub_pd(_mm256_sub_pd(x, _mm256_mul_pd(n, _mm256_set1_pd(0.693147180369123816490))),
                                  _mm256_mul_pd(n, _mm256_set1_pd(1.90821492927058770002e-10)));
  __m256d p = _mm256_set1_pd(1.0 / 6227020800.0);
  for (const double c : {1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0,
                         1.0 / 40320.0, 1.0 / 5040.0, 1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0,
                         1.0 / 6.0, 0.5, 1.0, 1.0})
    p = _mm256_add_pd(_mm256_mul_pd(p, r), _mm256_set1_pd(c));
  const __m256i ni = _mm256_sub_epi64(_mm256_castpd_si256(t), _mm256_castpd_si256(shifter));
  return _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(p), _mm256_slli_epi64(ni, 52)));
}
#endif

}  // namespace shadowlab
