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
//
// The vector forms (exp_d4 / exp_d8, log_d4 / log_d8, exp_f8 / exp_f16, exp_wide8 / exp_wide16,
// log_wide8 / log_wide16, log_split_f8 / log_split_f16) are written once, in
// core/exp_log_avx2.inl and core/exp_log_avx512.inl. An ISA file (*_avx2.cpp, *_avx512.cpp;
// docs/simd.md) includes core/exp_log_avx2.h or core/exp_log_avx512.h, which put them in their
// own namespaces as plain forced-inline functions.
#include <bit>
#include <cstdint>

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

}  // namespace shadowlab
