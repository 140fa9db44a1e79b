// msm_intensity (techniques/filters/msm/moment_bound.h) in AVX2 lanes of 4 doubles. Included inside the own
// namespace of a file compiled for AVX2 (docs/simd.md), after <immintrin.h>.

[[gnu::always_inline]] inline __m256d mul(__m256d x, __m256d y) { return _mm256_mul_pd(x, y); }
[[gnu::always_inline]] inline __m256d add(__m256d x, __m256d y) { return _mm256_add_pd(x, y); }
[[gnu::always_inline]] inline __m256d sub(__m256d x, __m256d y) { return _mm256_sub_pd(x, y); }
[[gnu::always_inline]] inline __m256d div(__m256d x, __m256d y) { return _mm256_div_pd(x, y); }

// msm_intensity for N groups of 4 lanes (m[h][i]: moment i + 1 of group h's lanes); N = 2
// overlaps two groups' chains of divisions, as msm_intensity8n does.
template <int N>
inline void msm_intensity4n(const __m256d (*m)[4], const __m256d* z, double alpha, bool hausdorff,
                            __m256d* out) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d keep = _mm256_set1_pd(1.0 - alpha), pull = _mm256_set1_pd(0.5 * alpha);
  __m256d b[N][4], d22[N], e32[N], s33[N], y2[N], y3s[N], c1[N], c2[N], c3[N];
  __m256d p[N], q[N], r[N], z2[N], z3[N], g[N];
  for (int h = 0; h < N; ++h)
    for (int i = 0; i < 4; ++i) b[h][i] = add(mul(m[h][i], keep), pull);
  // hankel_solve's scaled solve, then the one reciprocal.
  for (int h = 0; h < N; ++h) {
    d22[h] = sub(b[h][1], mul(b[h][0], b[h][0]));
    e32[h] = sub(b[h][2], mul(b[h][0], b[h][1]));
    s33[h] = sub(mul(d22[h], sub(b[h][3], mul(b[h][1], b[h][1]))), mul(e32[h], e32[h]));
    y2[h] = sub(z[h], b[h][0]);
    y3s[h] = sub(mul(d22[h], sub(mul(z[h], z[h]), b[h][1])), mul(e32[h], y2[h]));
    c3[h] = mul(d22[h], y3s[h]);
    c2[h] = sub(mul(s33[h], y2[h]), mul(e32[h], y3s[h]));
    c1[h] = sub(sub(mul(d22[h], s33[h]), mul(b[h][0], c2[h])), mul(b[h][1], c3[h]));
  }
  for (int h = 0; h < N; ++h) {
    const __m256d inv = div(one, c3[h]);
    p[h] = mul(c2[h], inv);
    q[h] = mul(c1[h], inv);
  }
  for (int h = 0; h < N; ++h)
    r[h] = _mm256_sqrt_pd(sub(mul(mul(p[h], p[h]), _mm256_set1_pd(0.25)), q[h]));
  for (int h = 0; h < N; ++h) {
    const __m256d hp = mul(_mm256_set1_pd(-0.5), p[h]);
    z2[h] = sub(hp, r[h]);
    z3[h] = add(hp, r[h]);
  }
  for (int h = 0; h < N; ++h) {
    // The weight's operands selected by branch, then one division (msm_intensity's bits).
    const __m256d zh = z[h], bh0 = b[h][0], bh1 = b[h][1];
    const __m256d mid = _mm256_cmp_pd(zh, z3[h], _CMP_LE_OQ);
    // Both numerators are (x·z3 − b1·(x + z3)) + b2, x = z or z2; both denominators
    // (z − z2)·(a − c), (a, c) = (z3, z2) or (z, z3) (a product's bits do not depend on its
    // order).
    const __m256d x = _mm256_blendv_pd(z2[h], zh, mid);
    const __m256d num = add(sub(mul(x, z3[h]), mul(bh0, add(x, z3[h]))), bh1);
    const __m256d den = mul(sub(zh, z2[h]), sub(_mm256_blendv_pd(zh, z3[h], mid),
                                                 _mm256_blendv_pd(z3[h], z2[h], mid)));
    const __m256d w = div(num, den);
    g[h] = _mm256_blendv_pd(sub(one, w), w, mid);
    g[h] = _mm256_blendv_pd(g[h], zero, _mm256_cmp_pd(zh, z2[h], _CMP_LE_OQ));
  }
  if (hausdorff) {
    for (int h = 0; h < N; ++h) {
      const __m256d outside = _mm256_or_pd(_mm256_cmp_pd(z2[h], zero, _CMP_LT_OQ),
                                           _mm256_cmp_pd(z3[h], one, _CMP_GT_OQ));
      if (_mm256_movemask_pd(outside) == 0) continue;
      const __m256d zh = z[h];
      const __m256d* bh = b[h];
      const __m256d zp1 = add(zh, one);
      const __m256d u = div(add(sub(bh[3], mul(zp1, bh[2])), mul(zh, bh[1])),
                            add(sub(bh[2], mul(zp1, bh[1])), mul(zh, bh[0])));
      const __m256d zu = mul(zh, u);
      const __m256d w0 = div(
          sub(add(sub(bh[2], mul(add(zp1, u), bh[1])), mul(add(add(zh, u), zu), bh[0])), zu),
          _mm256_xor_pd(zu, _mm256_set1_pd(-0.0)));
      const __m256d wu = div(add(sub(bh[2], mul(zp1, bh[1])), mul(zh, bh[0])),
                             mul(mul(u, sub(u, one)), sub(u, zh)));
      const __m256d g4 = _mm256_blendv_pd(w0, add(w0, wu), _mm256_cmp_pd(u, zh, _CMP_LT_OQ));
      g[h] = _mm256_blendv_pd(g[h], g4, outside);
    }
  }
  // g > 0 ? (g < 1 ? g : 1) : 0, NaN -> 0.
  for (int h = 0; h < N; ++h) {
    const __m256d positive = _mm256_cmp_pd(g[h], zero, _CMP_GT_OQ);
    const __m256d c = _mm256_blendv_pd(one, g[h], _mm256_cmp_pd(g[h], one, _CMP_LT_OQ));
    out[h] = _mm256_blendv_pd(zero, c, positive);
  }
}
