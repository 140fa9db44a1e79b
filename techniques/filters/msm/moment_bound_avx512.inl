// msm_intensity (techniques/filters/msm/moment_bound.h) in AVX-512 lanes of 8 doubles. Included inside the
// own namespace of a file compiled for AVX-512 (docs/simd.md), after <immintrin.h>.

[[gnu::always_inline]] inline __m512d mul(__m512d x, __m512d y) { return _mm512_mul_pd(x, y); }
[[gnu::always_inline]] inline __m512d add(__m512d x, __m512d y) { return _mm512_add_pd(x, y); }
[[gnu::always_inline]] inline __m512d sub(__m512d x, __m512d y) { return _mm512_sub_pd(x, y); }
[[gnu::always_inline]] inline __m512d div(__m512d x, __m512d y) { return _mm512_div_pd(x, y); }

// msm_intensity for N groups of 8 lanes (AVX-512 F and DQ): msm_intensity4n's operations with
// compare masks for its blends, so each lane gets the scalar bits; a division costs the same per
// instruction as in AVX2 on the machines we measure (AMD EPYC: ~1.15 ns either way), so 8 lanes
// halve the divisions' share of the MSM lookup. The chain of divisions and the square root is
// serial within a group; N > 1 issues independent groups' steps side by side so that one group's
// division runs while another's waits (the lookup takes 4 groups: docs/performance_history.md).
template <int N>
inline void msm_intensity8n(const __m512d (*m)[4], const __m512d* z, double alpha, bool hausdorff,
                            __m512d* out) {
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
  const __m512d keep = _mm512_set1_pd(1.0 - alpha), pull = _mm512_set1_pd(0.5 * alpha);
  __m512d b[N][4], d22[N], e32[N], s33[N], y2[N], y3s[N], c1[N], c2[N], c3[N];
  __m512d p[N], q[N], r[N], z2[N], z3[N], g[N];
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
    const __m512d inv = div(one, c3[h]);
    p[h] = mul(c2[h], inv);
    q[h] = mul(c1[h], inv);
  }
  // The zero-masked square root with every lane on: GCC 12's unmasked one passes an undefined
  // source that -Wuninitialized reports (the same instruction either way).
  for (int h = 0; h < N; ++h)
    r[h] = _mm512_maskz_sqrt_pd(0xFF, sub(mul(mul(p[h], p[h]), _mm512_set1_pd(0.25)), q[h]));
  for (int h = 0; h < N; ++h) {
    const __m512d hp = mul(_mm512_set1_pd(-0.5), p[h]);
    z2[h] = sub(hp, r[h]);
    z3[h] = add(hp, r[h]);
  }
  for (int h = 0; h < N; ++h) {
    // The weight's operands selected by branch, then one division (msm_intensity's bits).
    const __m512d zh = z[h], bh0 = b[h][0], bh1 = b[h][1];
    const __mmask8 mid = _mm512_cmp_pd_mask(zh, z3[h], _CMP_LE_OQ);
    // The operands selected as in msm_intensity4n.
    const __m512d x = _mm512_mask_blend_pd(mid, z2[h], zh);
    const __m512d num = add(sub(mul(x, z3[h]), mul(bh0, add(x, z3[h]))), bh1);
    const __m512d den = mul(sub(zh, z2[h]), sub(_mm512_mask_blend_pd(mid, zh, z3[h]),
                                                 _mm512_mask_blend_pd(mid, z3[h], z2[h])));
    const __m512d w = div(num, den);
    g[h] = _mm512_mask_blend_pd(mid, sub(one, w), w);
    g[h] = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(zh, z2[h], _CMP_LE_OQ), g[h], zero);
  }
  if (hausdorff) {
    for (int h = 0; h < N; ++h) {
      const __mmask8 outside = __mmask8(_mm512_cmp_pd_mask(z2[h], zero, _CMP_LT_OQ) |
                                        _mm512_cmp_pd_mask(z3[h], one, _CMP_GT_OQ));
      if (outside == 0) continue;
      const __m512d zh = z[h];
      const __m512d* bh = b[h];
      const __m512d zp1 = add(zh, one);
      const __m512d u = div(add(sub(bh[3], mul(zp1, bh[2])), mul(zh, bh[1])),
                            add(sub(bh[2], mul(zp1, bh[1])), mul(zh, bh[0])));
      const __m512d zu = mul(zh, u);
      const __m512d w0 = div(
          sub(add(sub(bh[2], mul(add(zp1, u), bh[1])), mul(add(add(zh, u), zu), bh[0])), zu),
          _mm512_xor_pd(zu, _mm512_set1_pd(-0.0)));
      const __m512d wu = div(add(sub(bh[2], mul(zp1, bh[1])), mul(zh, bh[0])),
                             mul(mul(u, sub(u, one)), sub(u, zh)));
      const __m512d g4 =
          _mm512_mask_blend_pd(_mm512_cmp_pd_mask(u, zh, _CMP_LT_OQ), w0, add(w0, wu));
      g[h] = _mm512_mask_blend_pd(outside, g[h], g4);
    }
  }
  // g > 0 ? (g < 1 ? g : 1) : 0, NaN -> 0.
  for (int h = 0; h < N; ++h) {
    const __mmask8 positive = _mm512_cmp_pd_mask(g[h], zero, _CMP_GT_OQ);
    const __m512d c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(g[h], one, _CMP_LT_OQ), one, g[h]);
    out[h] = _mm512_mask_blend_pd(positive, zero, c);
  }
}
