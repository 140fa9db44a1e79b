// The AVX-512 bodies of core/exp_log.h's vector exp and log: included by core/exp_log_avx512.h
// inside its namespace, each function declared with SL_EXP_LOG_AVX512 (forced inline there, so
// that no out-of-line copy is shared with code of another set), and by core/exp_log.h's
// target-attribute forms. Each performs its scalar function's IEEE operations in its order, so
// every lane gets the scalar bits (tests/core/exp_log_test.cpp).

SL_EXP_LOG_AVX512 __m512d exp_d8(__m512d x) {
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

SL_EXP_LOG_AVX512 __m512 exp_f16_poly(__m512 x, __m512i& ni) {
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

SL_EXP_LOG_AVX512 __m512 exp_f16(__m512 x) {
  __m512i ni;
  const __m512 p = exp_f16_poly(x, ni);
  // The zero-masked shift with every lane on, as in exp_d8.
  const __m512i q = _mm512_maskz_slli_epi32(0xFFFF, ni, 23);
  return _mm512_castsi512_ps(_mm512_add_epi32(_mm512_castps_si512(p), q));
}

// Halves of a 512-bit vector and two halves joined, in the zero-masked forms with every lane on:
// GCC 12's unmasked extracts and inserts (and the casts built on them) pass an undefined source
// that -Wmaybe-uninitialized reports, as in exp_d8.
SL_EXP_LOG_AVX512 __m256 half_ps(__m512 v, int hi) {
  return _mm256_castpd_ps(hi ? _mm512_maskz_extractf64x4_pd(0xF, _mm512_castps_pd(v), 1)
                             : _mm512_maskz_extractf64x4_pd(0xF, _mm512_castps_pd(v), 0));
}
SL_EXP_LOG_AVX512 __m256i half_si(__m512i v, int hi) {
  return hi ? _mm512_maskz_extracti64x4_epi64(0xF, v, 1)
            : _mm512_maskz_extracti64x4_epi64(0xF, v, 0);
}
SL_EXP_LOG_AVX512 __m512 join_ps(__m256 lo, __m256 hi) {
  return _mm512_castpd_ps(_mm512_maskz_insertf64x4(
      0xFF, _mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}

SL_EXP_LOG_AVX512 __m512d scale_wide8(__m256 p, __m256i n) {
  const __m512i q = _mm512_maskz_slli_epi64(0xFF, _mm512_maskz_cvtepi32_epi64(0xFF, n), 52);
  return _mm512_castsi512_pd(
      _mm512_add_epi64(_mm512_castpd_si512(_mm512_maskz_cvtps_pd(0xFF, p)), q));
}

SL_EXP_LOG_AVX512 void exp_wide16(__m512 x, __m512d& lo, __m512d& hi) {
  __m512i ni;
  const __m512 p = exp_f16_poly(x, ni);
  lo = scale_wide8(half_ps(p, 0), half_si(ni, 0));
  hi = scale_wide8(half_ps(p, 1), half_si(ni, 1));
}

SL_EXP_LOG_AVX512 __m512d log_d8(__m512d x) {
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

// log_wide's split of 8 positive normal doubles, x = m·2^e with m in [0.75, 1.5): getmant's
// [0.75, 1.5) interval is that m exactly (the [1, 2) mantissa, halved from 1.5 on), getexp the
// exponent of x's [1, 2) form, one more where the mantissa was halved; the two instructions do
// what log_wide's eleven integer steps do, in fewer instructions.
// Returns m as floats; e as doubles (exact integers). The zero-masked forms with every lane on:
// GCC 12's unmasked ones trip -Wmaybe-uninitialized, as in exp_d8.
SL_EXP_LOG_AVX512 __m256 log_wide_m8(__m512d x, __m512d& e) {
  const __m512d m = _mm512_maskz_getmant_pd(0xFF, x, _MM_MANT_NORM_p75_1p5, _MM_MANT_SIGN_src);
  const __m512d g = _mm512_maskz_getexp_pd(0xFF, x);
  const __m512d one = _mm512_set1_pd(1.0);
  e = _mm512_mask_add_pd(g, _mm512_cmp_pd_mask(m, one, _CMP_LT_OQ), g, one);
  return _mm512_maskz_cvtpd_ps(0xFF, m);
}

SL_EXP_LOG_AVX512 __m512 ln_m16(__m512 mf) {
  const __m512 one = _mm512_set1_ps(1.0f);
  const __m512 s = _mm512_div_ps(_mm512_sub_ps(mf, one), _mm512_add_ps(mf, one));
  const __m512 s2 = _mm512_mul_ps(s, s);
  __m512 q = _mm512_set1_ps(1.0f / 9.0f);
  for (const float k : {1.0f / 7.0f, 1.0f / 5.0f, 1.0f / 3.0f})
    q = _mm512_add_ps(_mm512_mul_ps(q, s2), _mm512_set1_ps(k));
  const __m512 two_s = _mm512_add_ps(s, s);
  return _mm512_add_ps(two_s, _mm512_mul_ps(two_s, _mm512_mul_ps(s2, q)));
}

SL_EXP_LOG_AVX512 void log_wide16(__m512d x_lo, __m512d x_hi, __m512d& lo,
                                            __m512d& hi) {
  __m512d e_lo, e_hi;
  const __m256 m_lo = log_wide_m8(x_lo, e_lo), m_hi = log_wide_m8(x_hi, e_hi);
  const __m512 ln_m = ln_m16(join_ps(m_lo, m_hi));
  const __m512d ln2 = _mm512_set1_pd(0.6931471805599453);
  lo = _mm512_add_pd(_mm512_mul_pd(e_lo, ln2), _mm512_maskz_cvtps_pd(0xFF, half_ps(ln_m, 0)));
  hi = _mm512_add_pd(_mm512_mul_pd(e_hi, ln2), _mm512_maskz_cvtps_pd(0xFF, half_ps(ln_m, 1)));
}

// (The zero-masked shifts with every lane on, as in exp_f16.)
SL_EXP_LOG_AVX512 __m512 log_split_f16(__m512 x, __m512i& e) {
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
