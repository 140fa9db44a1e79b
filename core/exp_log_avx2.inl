// The AVX2 bodies of core/exp_log.h's vector exp and log: included by core/exp_log_avx2.h (and
// core/exp_log_avx512.h) inside their namespaces, each function declared with SL_EXP_LOG_AVX2
// (forced inline there, so that no out-of-line copy is shared with code of another set), and
// by core/exp_log.h's target-attribute forms. Each performs its scalar function's IEEE
// operations in its order, so every lane gets the scalar bits (tests/core/exp_log_test.cpp).

// exp_d of 4 and of 8 doubles with AVX2 and AVX-512 intrinsics: exp_d's operations in exp_d's
// order, the table read by a gather (AVX2) or a two-register permute (AVX-512), so each lane
// gets exp_d's bits (tests/core/exp_log_test.cpp), for kernels written with intrinsics.
SL_EXP_LOG_AVX2 __m256d exp_d4(__m256d x) {
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

// exp_f of 8 floats (AVX2) and of 16 (AVX-512): exp_f's operations in exp_f's order, so each
// lane gets exp_f's bits (tests/core/exp_log_test.cpp), for the EVSM filter's rows and the
// ESM lookup's AVX2 batch.
SL_EXP_LOG_AVX2 __m256 exp_f8_poly(__m256 x, __m256i& ni) {
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

SL_EXP_LOG_AVX2 __m256 exp_f8(__m256 x) {
  __m256i ni;
  const __m256 p = exp_f8_poly(x, ni);
  return _mm256_castsi256_ps(_mm256_add_epi32(_mm256_castps_si256(p), _mm256_slli_epi32(ni, 23)));
}

// p · 2^n for floats p and int32 n, widened: n shifted into the double's exponent field.
SL_EXP_LOG_AVX2 __m256d scale_wide4(__m128 p, __m128i n) {
  const __m256i q = _mm256_slli_epi64(_mm256_cvtepi32_epi64(n), 52);
  return _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(_mm256_cvtps_pd(p)), q));
}

// exp_wide of 8 floats (AVX2) and of 16 (AVX-512, below), lanes 0..3 / 0..7 into lo and the
// rest into hi: exp_f's float steps, then p widened and 2^ni added to its exponent in 64-bit
// lanes, so each lane gets exp_wide's bits (tests/core/exp_log_test.cpp).
SL_EXP_LOG_AVX2 void exp_wide8(__m256 x, __m256d& lo, __m256d& hi) {
  __m256i ni;
  const __m256 p = exp_f8_poly(x, ni);
  lo = scale_wide4(_mm256_castps256_ps128(p), _mm256_castsi256_si128(ni));
  hi = scale_wide4(_mm256_extractf128_ps(p, 1), _mm256_extracti128_si256(ni, 1));
}

// log_d of 4 and of 8 doubles, as exp_d4 and exp_d8 are to exp_d (tables by gathers, or by
// two-register permutes).
SL_EXP_LOG_AVX2 __m256d log_d4(__m256d x) {
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

// log_wide's split of 4 (8, below) doubles: e, and m rounded to float.
SL_EXP_LOG_AVX2 __m128 log_wide_m4(__m256d x, __m256d& e) {
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
SL_EXP_LOG_AVX2 __m256 ln_m8(__m256 mf) {
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
SL_EXP_LOG_AVX2 void log_wide8(__m256d x_lo, __m256d x_hi, __m256d& lo, __m256d& hi) {
  __m256d e_lo, e_hi;
  const __m128 m_lo = log_wide_m4(x_lo, e_lo), m_hi = log_wide_m4(x_hi, e_hi);
  const __m256 ln_m = ln_m8(_mm256_set_m128(m_hi, m_lo));
  const __m256d ln2 = _mm256_set1_pd(0.6931471805599453);
  lo = _mm256_add_pd(_mm256_mul_pd(e_lo, ln2), _mm256_cvtps_pd(_mm256_castps256_ps128(ln_m)));
  hi = _mm256_add_pd(_mm256_mul_pd(e_hi, ln2), _mm256_cvtps_pd(_mm256_extractf128_ps(ln_m, 1)));
}

// log_split_f of 8 floats (AVX2) and of 16 (AVX-512): the same integer steps in 32-bit lanes,
// so each lane gets log_split_f's m and e (tests/core/exp_log_test.cpp).
SL_EXP_LOG_AVX2 __m256 log_split_f8(__m256 x, __m256i& e) {
  const __m256i bits = _mm256_castps_si256(x);
  const __m256i up = _mm256_and_si256(_mm256_srli_epi32(bits, 22), _mm256_set1_epi32(1));
  e = _mm256_sub_epi32(_mm256_add_epi32(_mm256_srli_epi32(bits, 23), up), _mm256_set1_epi32(127));
  const __m256i m_exp =
      _mm256_sub_epi32(_mm256_set1_epi32(0x3F800000), _mm256_slli_epi32(up, 23));
  return _mm256_castsi256_ps(
      _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi32(0x007FFFFF)), m_exp));
}
