// The plain-loop rows of techniques/filters/moments_common/moment_rows.h, written once and included inside the own
// namespace of each table's file (moment_rows.cpp: baseline; moment_rows_avx2.cpp,
// moment_rows_avx512.cpp), which the compiler vectorizes for that file's set. Each loop runs over
// x and performs one texel's IEEE operations in a fixed order, so vectorizing reorders nothing
// any one texel sees. Also the one-texel helpers the hand-written rows use for heads and tails.
// Needs core/exp_log.h and techniques/filters/msm/moment_bound.h (exp_f, exp_wide, log_wide, msm_encode16),
// <bit>, <cmath>, <cstdint> included before the namespace.

// Distance with "nothing seen" as the light's range: d < 1 ? d : 1.
[[gnu::always_inline]] inline float finite_dist(float d) { return d < 1.0f ? d : 1.0f; }

// finite_dist and v > 0 ? v : +0 as bit masks: the same values, but a compare turned into an
// integer mask is no control flow, so GCC vectorizes it whatever the file's set.
[[gnu::always_inline]] inline float finite_dist_bits(float d) {
  const uint32_t keep = uint32_t(0) - uint32_t(d < 1.0f);
  return std::bit_cast<float>((std::bit_cast<uint32_t>(d) & keep) |
                              (std::bit_cast<uint32_t>(1.0f) & ~keep));
}
[[gnu::always_inline]] inline double positive_part(double v) {
  const uint64_t keep = uint64_t(0) - uint64_t(v > 0.0);
  return std::bit_cast<double>(std::bit_cast<uint64_t>(v) & keep);
}

// Texels to write one by one before out + S·x starts a 64-byte line (S floats per texel), so the
// vector stores after them do not straddle cache lines: large vectors' storage is 16-byte
// aligned here (glibc's mmap chunks), and a 64-byte store across two lines costs about two.
// A row whose texels never start a line returns `unreachable`: 0 for ordinary stores (they may
// straddle), w where the stores need aligned addresses (then every texel goes one by one).
[[gnu::always_inline]] inline int texels_to_line(const float* out, int floats_per_texel, int w,
                                                 int unreachable = 0) {
  const uintptr_t bytes = (64 - (reinterpret_cast<uintptr_t>(out) & 63)) & 63;
  const uintptr_t texel_bytes = uintptr_t(floats_per_texel) * 4;
  if (bytes % texel_bytes != 0) return unreachable;
  const int n = int(bytes / texel_bytes);
  return n < w ? n : w;
}

// --- runtime-width rows ---------------------------------------------------------------------

template <class T>
void hsum_row(const T* ext, int w, int k, T* out) {
  for (int x = 0; x < w; ++x) out[x] = T(0);
  for (int i = 0; i < k; ++i)
    for (int x = 0; x < w; ++x) out[x] += ext[x + i];
}

template <class T>
void vsum_rows(const T* const* rows, int w, int k, T inv, T* dst) {
  for (int x = 0; x < w; ++x) dst[x] = rows[0][x];
  for (int j = 1; j < k; ++j)
    for (int x = 0; x < w; ++x) dst[x] += rows[j][x];
  for (int x = 0; x < w; ++x) dst[x] *= inv;
}

// --- per-texel rows ---------------------------------------------------------------------------

void finite_row(const float* row, int n, float* out) {
  for (int x = 0; x < n; ++x) out[x] = finite_dist_bits(row[x]);
}

void moment_row(const float* row, int w, double* m1, double* m2) {
  for (int x = 0; x < w; ++x) {
    const double d = double(finite_dist_bits(row[x]));
    m1[x] = d;
    m2[x] = d * d;
  }
}

void mean_variance_row(const double* m1, const double* m2, int w, float* mean, float* var) {
  for (int x = 0; x < w; ++x) {
    mean[x] = float(m1[x]);
    const double v = m2[x] - m1[x] * m1[x];
    var[x] = float(positive_part(v));
  }
}

// EVSM's warp in float, its moments in double. Why float is exact enough for the warp: its
// rounding moves v by at most ~4e-6 relative (the argument's roundings, |x| <= 44.4, and
// exp_f's 2 ulp), which is what a change of d by 1–2 of its own float ulps does (dv/v = 2c·dd,
// c <= 44.4); the variance, whose cancellation needs double, is formed from the double sums
// (docs/techniques/evsm.md).
void warped_row(const float* row, int w, double c, double sign, double* m1, double* m2) {
  const float sc = float(sign * c);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    const double v = sign * double(exp_f(sc * ((d + d) - 1.0f)));
    m1[x] = v;
    m2[x] = v * v;
  }
}

// The float warp as a loop (the scalar table's row, the hand-written rows' tails): the value
// warped_row forms (its v is that float, widened; sign = ±1, so the product is exact).
void warp_row_f_loop(const float* row, int w, double c, double sign, float* v) {
  const float sc = float(sign * c), fs = float(sign);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    v[x] = fs * exp_f(sc * ((d + d) - 1.0f));
  }
}

// A zip the compiler vectorizes (the strided stores of writing the interleaved row directly did
// not, and made the VSM filter ~25 % slower).
void interleave_row(const float* a, const float* b, int w, float* out) {
  const int head = texels_to_line(out, 2, w);
  for (int x = 0; x < head; ++x) {
    out[2 * x] = a[x];
    out[2 * x + 1] = b[x];
  }
  for (int x = head; x < w; ++x) {
    out[2 * x] = a[x];
    out[2 * x + 1] = b[x];
  }
}

void power_row(const float* row, int w, size_t stride, float* p) {
  for (int x = 0; x < w; ++x) p[x] = finite_dist_bits(row[x]);
  for (int x = 0; x < w; ++x) {
    const float d = p[x], d2 = d * d;
    p[stride + size_t(x)] = d2;
    p[2 * stride + size_t(x)] = d2 * d;
    p[3 * stride + size_t(x)] = d2 * d2;
  }
}

void interleave4_row(const float* rows, int w, float* out) {
  const int head = texels_to_line(out, 4, w);
  for (int x = 0; x < head; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
  for (int x = head; x < w; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
}

// floor is exact (one instruction from SSE4.1 on), so every set gives the same bits.
void quantize16(size_t n, float* __restrict mv) {
  for (size_t i = 0; i < n; ++i) {
    const double m[4] = {mv[4 * i], mv[4 * i + 1], mv[4 * i + 2], mv[4 * i + 3]};
    double q[4];
    msm_encode16(m, q);
    float r[4];
    for (int c = 0; c < 4; ++c) {
      const double v = q[c] < 0.0 ? 0.0 : (q[c] > 1.0 ? 1.0 : q[c]);
      r[c] = float(std::floor(v * 65535.0 + 0.5) / 65535.0);
    }
    for (int c = 0; c < 4; ++c) mv[4 * i + c] = r[c];
  }
}

// ESM's exponent rounded once to float: c·(d − d_min) in double (d − d_min is exact there).
// Why float precision is enough here: docs/techniques/esm.md, precision.
[[gnu::always_inline]] inline float esm_exponent(float d, double c, double d_min) {
  return float(c * (double(d) - d_min));
}
void esm_exp_row_loop(const float* row, int w, double c, double d_min, double* out) {
  for (int x = 0; x < w; ++x) out[x] = exp_wide(esm_exponent(finite_dist_bits(row[x]), c, d_min));
}

void esm_log_row(const double* filtered, int w, double c, double d_min, float* out) {
  for (int x = 0; x < w; ++x) out[x] = float(c * d_min + log_wide(filtered[x]));
}

// In 8 lanes combined in a fixed order (min is exact, so any order gives the same value).
float row_min_dist(const float* row, int w) {
  float lanes[8] = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  int x = 0;
  for (; x + 8 <= w; x += 8)
    for (int l = 0; l < 8; ++l) {
      const float d = finite_dist_bits(row[x + l]);
      const uint32_t take = uint32_t(0) - uint32_t(d < lanes[l]);
      lanes[l] = std::bit_cast<float>((std::bit_cast<uint32_t>(d) & take) |
                                      (std::bit_cast<uint32_t>(lanes[l]) & ~take));
    }
  float m = 1.0f;
  for (int l = 0; l < 8; ++l) m = lanes[l] < m ? lanes[l] : m;
  for (; x < w; ++x) {
    const float d = finite_dist(row[x]);
    m = d < m ? d : m;
  }
  return m;
}

// --- fixed-width rows -------------------------------------------------------------------------
// The same additions as the runtime-width rows, in the same order: a sum starts from 0 (as
// hsum_row does) and adds left to right, rows top to bottom, then × 1/k².

template <int K>
void hsum_k(const double* ext, int w, double* h) {
  for (int x = 0; x < w; ++x) {
    double s = 0.0;
    for (int i = 0; i < K; ++i) s += ext[x + i];
    h[x] = s;
  }
}

template <int K>
void hsum_moments_k(const float* ext, int w, double* h1, double* h2) {
  for (int x = 0; x < w; ++x) {
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < K; ++i) {
      const double d = double(ext[x + i]);
      s1 += d;
      s2 += d * d;
    }
    h1[x] = s1;
    h2[x] = s2;
  }
}

template <int K>
void vsm_out_k(const double* const* rows, int w, double inv, float* mean, float* var) {
  const double* r1[K];
  const double* r2[K];
  for (int j = 0; j < K; ++j) {
    r1[j] = rows[j];
    r2[j] = rows[K + j];
  }
  for (int x = 0; x < w; ++x) {
    double a = r1[0][x], b = r2[0][x];
    for (int j = 1; j < K; ++j) {
      a += r1[j][x];
      b += r2[j][x];
    }
    a *= inv;
    b *= inv;
    mean[x] = float(a);
    const double v = b - a * a;
    var[x] = float(positive_part(v));
  }
}

// One texel of hsum_powers_k: the four sums at x (also the fused rows' heads and tails).
template <int K>
[[gnu::always_inline]] inline void hsum_powers_texel(const float* ext, int x, float* const* h) {
  float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
  for (int i = 0; i < K; ++i) {
    const float d = ext[x + i], d2 = d * d;
    s0 += d;
    s1 += d2;
    s2 += d2 * d;
    s3 += d2 * d2;
  }
  h[0][x] = s0;
  h[1][x] = s1;
  h[2][x] = s2;
  h[3][x] = s3;
}

// hsum_k's sums of power_row's planes, without writing the planes.
template <int K>
void hsum_powers_k(const float* ext, int w, float* h0, float* h1, float* h2, float* h3) {
  float* const h[4] = {h0, h1, h2, h3};
  for (int x = 0; x < w; ++x) hsum_powers_texel<K>(ext, x, h);
}

template <int K>
void mean_out_k(const float* const* rows, int w, float inv, float* out) {
  const float* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  for (int x = 0; x < w; ++x) {
    float a = r[0][x];
    for (int j = 1; j < K; ++j) a += r[j][x];
    out[x] = a * inv;
  }
}

template <int K>
void esm_out_k_loop(const double* const* rows, int w, double inv, double c, double d_min,
                    float* out) {
  const double* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  for (int x = 0; x < w; ++x) {
    double a = r[0][x];
    for (int j = 1; j < K; ++j) a += r[j][x];
    a *= inv;
    out[x] = float(c * d_min + log_wide(a));
  }
}

// rows[0][x] + … + rows[K − 1][x] in row order, for one texel.
template <int K>
[[gnu::always_inline]] inline double sum_rows(const double* const* rows, int x) {
  double a = rows[0][x];
  for (int j = 1; j < K; ++j) a += rows[j][x];
  return a;
}
// One texel of the fused VSM output rows (their heads and tails): (mean, variance) from
// rows[0 .. K − 1] and rows[K .. 2K − 1], vsm_out_k's operations.
template <int K>
[[gnu::always_inline]] inline void vsm_out_texel(const double* const* rows, int x, double inv,
                                                 float* out) {
  const double a = sum_rows<K>(rows, x) * inv, b = sum_rows<K>(rows + K, x) * inv;
  out[2 * x] = float(a);
  out[2 * x + 1] = float(positive_part(b - a * a));
}
// One texel of the fused MSM output rows: the four means from plane c's rows[c·K ..
// c·K + K − 1], summed in float (mean_out_k's operations).
template <int K>
[[gnu::always_inline]] inline void msm_out_texel(const float* const* rows, int x, float inv,
                                                 float* out) {
  for (int c = 0; c < 4; ++c) {
    float a = rows[c * K][x];
    for (int j = 1; j < K; ++j) a += rows[c * K + j][x];
    out[4 * x + c] = a * inv;
  }
}

// The table's plain-loop entries, for `isa`; the file fills in its hand-written ones.
template <class Fn>
constexpr void set_widths(Fn (&slots)[kMomentWidths], Fn k1, Fn k3, Fn k5, Fn k7, Fn k9) {
  slots[0] = k1;
  slots[1] = k3;
  slots[2] = k5;
  slots[3] = k7;
  slots[4] = k9;
}
#define SL_MOMENT_WIDTHS(f) f<1>, f<3>, f<5>, f<7>, f<9>
constexpr MomentRowKernels plain_table(Isa isa) {
  MomentRowKernels t{};
  t.isa = isa;
  t.hsum_row_d = hsum_row<double>;
  t.hsum_row_f = hsum_row<float>;
  t.vsum_rows_d = vsum_rows<double>;
  t.vsum_rows_f = vsum_rows<float>;
  t.finite_row = finite_row;
  t.moment_row = moment_row;
  t.mean_variance_row = mean_variance_row;
  t.warped_row = warped_row;
  t.warp_row_f = warp_row_f_loop;
  t.interleave_row = interleave_row;
  t.power_row = power_row;
  t.interleave4_row = interleave4_row;
  t.quantize16 = quantize16;
  t.esm_exp_row = esm_exp_row_loop;
  t.esm_log_row = esm_log_row;
  t.row_min_dist = row_min_dist;
  set_widths(t.hsum_k, SL_MOMENT_WIDTHS(hsum_k));
  set_widths(t.hsum_moments_k, SL_MOMENT_WIDTHS(hsum_moments_k));
  set_widths(t.vsm_out_k, SL_MOMENT_WIDTHS(vsm_out_k));
  set_widths(t.hsum_powers_k, SL_MOMENT_WIDTHS(hsum_powers_k));
  set_widths(t.mean_out_k, SL_MOMENT_WIDTHS(mean_out_k));
  set_widths(t.esm_out_k, SL_MOMENT_WIDTHS(esm_out_k_loop));
  return t;
}
