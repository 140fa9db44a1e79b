// The vector row of techniques/filters/moments_common/centred_window3.h, written once for the lanes of
// core/lanes_avx2.h and core/lanes_avx512.h (Vf, kLanes, vadd, ...). Included, inside its own
// namespace, by centred_window3_avx2.cpp and centred_window3_avx512.cpp, each of which first
// defines store_zip(out, mean, var): its instruction set's interleave of kLanes texels' means
// and variances into 2·kLanes floats at out. The heads and tails are the scalar texel's loop
// (centred_window3_texel.inl), compiled for the same set.

#include "techniques/filters/moments_common/centred_window3_texel.inl"

// Texels to compute one by one before the interleaved output (8 bytes per texel) starts a
// 64-byte line, so the vector stores after them do not straddle lines (a store across two
// lines costs about two); n when no texel boundary falls on a line (then every texel goes one
// by one, which only a misaligned caller's storage would cause).
inline int texels_to_line(const float* out, int n) {
  const uintptr_t bytes = (64 - (reinterpret_cast<uintptr_t>(out) & 63)) & 63;
  if (bytes % 8 != 0) return n;
  return int(bytes / 8) < n ? int(bytes / 8) : n;
}

// kLanes texels' mean and variance from x on: window_texel's operations lane by lane.
inline void window(const float* r0, const float* r1, const float* r2, int x, Vf& mean,
                   Vf& var) {
  const Vf c = vloadu(r1 + x + 1), third = vset1(kThird);
  const Vf zero = vzero();
  Vf s1 = zero, s2 = zero;
  // An array, not an initializer_list: no library code in an ISA file (docs/simd.md).
  const float* const rows[3] = {r0, r1, r2};
  for (const float* r : rows)
    for (int i = 0; i < 3; ++i) {
      const Vf d = vsub(vloadu(r + x + i), c);
      s1 = vadd(s1, d);
      const Vf u = vmul(d, third);
      s2 = vadd(s2, vmul(u, u));
    }
  const Vf m = vmul(s1, vset1(kNinth));
  mean = vadd(c, m);
  var = vpositive(vsub(s2, vmul(m, m)));
}

void row(const float* r0, const float* r1, const float* r2, int n, float* mean, float* var,
         int stride) {
  const bool zip = stride == 2 && var == mean + 1;
  int x = zip ? texels_to_line(mean, n) : 0;
  scalar_span(r0, r1, r2, 0, x, mean, var, stride);
  for (; x + kLanes <= n; x += kLanes) {
    Vf m, v;
    window(r0, r1, r2, x, m, v);
    if (zip) {
      store_zip(mean + 2 * x, m, v);
      continue;
    }
    alignas(64) float mb[kLanes], vb[kLanes];
    vstore(mb, m);
    vstore(vb, v);
    for (int l = 0; l < kLanes; ++l) {
      mean[size_t(stride) * size_t(x + l)] = mb[l];
      var[size_t(stride) * size_t(x + l)] = vb[l];
    }
  }
  scalar_span(r0, r1, r2, x, n, mean, var, stride);
}
