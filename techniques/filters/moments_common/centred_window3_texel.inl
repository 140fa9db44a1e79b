// The scalar texel of techniques/filters/moments_common/centred_window3.h and the loop over a span of texels, included
// inside their own namespace by centred_window3.cpp (the scalar table) and by
// centred_window3_simd.inl (the vector rows' heads and tails, compiled for their set as the
// rest of the row is; the same operations, so the same bits).

// 1/3 and 1/9 rounded to float: the kernels multiply by them (a product per lane is cheaper
// than a division, and every kernel uses the same constants, so the same bits).
constexpr float kThird = 1.0f / 3.0f;
constexpr float kNinth = 1.0f / 9.0f;

// Texel x of a row: the header's sums, in window order, then the mean and the positive part of
// the variance (a NaN gives +0, as v > 0 is false for it).
inline void window_texel(const float* r0, const float* r1, const float* r2, int x, float& mean,
                         float& var) {
  const float c = r1[x + 1];
  float s1 = 0.0f, s2 = 0.0f;
  const float* const rows[3] = {r0, r1, r2};  // an array: no library code in an ISA file
  for (const float* r : rows)
    for (int i = 0; i < 3; ++i) {
      const float d = r[x + i] - c;
      s1 += d;
      const float u = d * kThird;
      s2 += u * u;
    }
  const float m = s1 * kNinth;
  mean = c + m;
  const float v = s2 - m * m;
  var = v > 0.0f ? v : 0.0f;
}

// Texels x = from .. n − 1 of a row.
void scalar_span(const float* r0, const float* r1, const float* r2, int from, int n, float* mean,
                 float* var, int stride) {
  for (int x = from; x < n; ++x)
    window_texel(r0, r1, r2, x, mean[size_t(stride) * size_t(x)], var[size_t(stride) * size_t(x)]);
}
