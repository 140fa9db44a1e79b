#include "techniques/filters/moments_common/moment_filter.h"

#include "techniques/filters/moments_common/moment_box.h"

namespace shadowlab {
namespace {

// Separable box filter of N planes (T = double or float), clamp-to-edge, giving the mean over
// the k × k footprint: horizontal sums into tmp, then vertical sums into out. Every output is
// the same fixed-order sum of its window, whatever the chunking.
template <class T, int N>
void box_mean(const std::vector<T>* in, int w, int h, int k, std::vector<T>* tmp,
              std::vector<T>* out) {
  const int r = k / 2;
  const size_t n = size_t(w) * size_t(h);
  for (int c = 0; c < N; ++c) {
    tmp[c].resize(n);
    out[c].resize(n);
  }
  const T inv = T(1) / T(k * k);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int c = 0; c < N; ++c) {
        const T* row = in[c].data() + y * size_t(w);
        T* dst = tmp[c].data() + y * size_t(w);
        // Borders clamp; the interior needs no index checks.
        auto clamped = [&](int x) {
          T s = 0;
          for (int i = -r; i <= r; ++i) s += row[std::clamp(x + i, 0, w - 1)];
          return s;
        };
        const int lo = std::min(r, w), hi = std::max(lo, w - r);
        for (int x = 0; x < lo; ++x) dst[x] = clamped(x);
        for (int x = lo; x < hi; ++x) {
          T s = 0;
          for (int i = -r; i <= r; ++i) s += row[x + i];
          dst[x] = s;
        }
        for (int x = hi; x < w; ++x) dst[x] = clamped(x);
      }
  });
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int c = 0; c < N; ++c) {
        T* dst = out[c].data() + y * size_t(w);
        const T* first = tmp[c].data() + size_t(std::clamp(int(y) - r, 0, h - 1)) * size_t(w);
        for (int x = 0; x < w; ++x) dst[x] = first[x];
        for (int j = -r + 1; j <= r; ++j) {
          const T* row = tmp[c].data() + size_t(std::clamp(int(y) + j, 0, h - 1)) * size_t(w);
          for (int x = 0; x < w; ++x) dst[x] += row[x];
        }
        for (int x = 0; x < w; ++x) dst[x] *= inv;
      }
  });
}

// Per-texel moments (d, d² [+ slope term]) in type T.
template <class T>
void raw_moments(const float* dist, int w, int h, bool slope_term, std::vector<T>& m1,
                 std::vector<T>& m2) {
  const size_t n = size_t(w) * size_t(h);
  m1.resize(n);
  m2.resize(n);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = y * size_t(w) + size_t(x);
        const T d = T(finite_dist(dist[i]));
        m1[i] = d;
        m2[i] = d * d;
        if (slope_term) {
          auto at = [&](int xx, int yy) {
            return double(finite_dist(dist[size_t(std::clamp(yy, 0, h - 1)) * size_t(w) +
                                           size_t(std::clamp(xx, 0, w - 1))]));
          };
          const int yi = int(y);
          const double dx = min_diff(at(x - 1, yi), double(d), at(x + 1, yi));
          const double dy = min_diff(at(x, yi - 1), double(d), at(x, yi + 1));
          m2[i] += T(0.25 * (dx * dx + dy * dy));
        }
      }
  });
}

// Row r of raw_moments without the slope term: m1 = d, m2 = d² (d = finite_dist).
SL_ROW_CLONES void moment_row(const float* row, int w, double* m1, double* m2) {
  for (int x = 0; x < w; ++x) {
    const double d = double(finite_dist_bits(row[x]));
    m1[x] = d;
    m2[x] = d * d;
  }
}

// Mean and variance floats of filtered moment rows (filter_moments_double's storage).
SL_ROW_CLONES void mean_variance_row(const double* m1, const double* m2, int w, float* mean,
                                    float* var) {
  for (int x = 0; x < w; ++x) {
    mean[x] = float(m1[x]);
    const double v = m2[x] - m1[x] * m1[x];
    var[x] = float(positive_part(v));
  }
}

// EVSM's warped moments of one row: m1 = v = sign·e^(sign·c·(2d − 1)), m2 = v², the warp in
// float (exp_f of float(sign·c)·((d + d) − 1)), its moments and sums in double. Why float is
// exact enough for the warp: its rounding moves v by at most ~4e-6 relative (the argument's
// roundings, |x| <= 44.4, and exp_f's 2 ulp), which is what a change of d by 1–2 of its own
// float ulps does (dv/v = 2c·dd, c <= 44.4); the variance, whose cancellation needs double, is
// formed from the double sums (docs/techniques/evsm.md).
SL_ROW_CLONES void warped_row_scalar(const float* row, int w, double c, double sign, double* m1,
                                     double* m2) {
  const float sc = float(sign * c);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    const double v = sign * double(exp_f(sc * ((d + d) - 1.0f)));
    m1[x] = v;
    m2[x] = v * v;
  }
}

#if defined(__x86_64__)
// EVSM's warp alone, as floats: v[x] = sign·exp_f(float(sign·c)·((d + d) − 1)), the value
// warped_row_scalar forms (its v is that float, widened; sign = ±1, so the product is exact).
// The fixed-width path sums these floats' moments by hsum_moments_k (v and v² formed in double
// there, as VSM's are), so the row kernel writes 4 bytes per texel instead of two doubles' 16.
// 16 (AVX-512) and 8 (AVX2) floats at a time by exp_f16 / exp_f8; min(d, 1) is finite_dist as
// above; the tail by the scalar loop.
SL_ROW_CLONES void warp_row_f_scalar(const float* row, int w, double c, double sign, float* v) {
  const float sc = float(sign * c), fs = float(sign);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    v[x] = fs * exp_f(sc * ((d + d) - 1.0f));
  }
}

SL_TARGET("avx512f") void warp_row_f_avx512(const float* row, int w, double c,
                                            double sign, float* v) {
  const __m512 one = _mm512_set1_ps(1.0f), sc = _mm512_set1_ps(float(sign * c));
  const __m512 fs = _mm512_set1_ps(float(sign));
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    // (Zero-masked forms with every lane on, for GCC 12's -Wmaybe-uninitialized: exp_d8.)
    const __m512 d = _mm512_maskz_min_ps(0xFFFF, _mm512_loadu_ps(row + x), one);
    const __m512 e = exp_f16(_mm512_mul_ps(sc, _mm512_sub_ps(_mm512_add_ps(d, d), one)));
    _mm512_storeu_ps(v + x, _mm512_mul_ps(fs, e));
  }
  warp_row_f_scalar(row + x, w - x, c, sign, v + x);
}

SL_TARGET("avx2") void warp_row_f_avx2(const float* row, int w, double c,
                                       double sign, float* v) {
  const __m256 one = _mm256_set1_ps(1.0f), sc = _mm256_set1_ps(float(sign * c));
  const __m256 fs = _mm256_set1_ps(float(sign));
  int x = 0;
  for (; x + 8 <= w; x += 8) {
    const __m256 d = _mm256_min_ps(_mm256_loadu_ps(row + x), one);
    const __m256 e = exp_f8(_mm256_mul_ps(sc, _mm256_sub_ps(_mm256_add_ps(d, d), one)));
    _mm256_storeu_ps(v + x, _mm256_mul_ps(fs, e));
  }
  warp_row_f_scalar(row + x, w - x, c, sign, v + x);
}
#endif

void warp_row_f(Isa path, const float* row, int w, double c, double sign, float* v) {
#if defined(__x86_64__)
  if (path == Isa::avx512) return warp_row_f_avx512(row, w, c, sign, v);
  if (path == Isa::avx2) return warp_row_f_avx2(row, w, c, sign, v);
#endif
  warp_row_f_scalar(row, w, c, sign, v);
}

// VSM: h1[x] = Σ_i d, h2[x] = Σ_i d² over ext[x .. x + K − 1] (ext: the clamped finite row).
template <int K>
SL_ROW_CLONES void hsum_moments_k(const float* ext, int w, double* h1, double* h2) {
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

// VSM: the K rows of both planes summed, × inv, stored as mean and variance floats.
template <int K>
SL_ROW_CLONES void vsm_out_k(const double* const* rows, int w, double inv, float* mean,
                             float* var) {
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

// out[2x] = a[x], out[2x + 1] = b[x]: two rows into one interleaved row (a zip the compiler
// vectorizes; the strided stores of writing the interleaved row directly did not, and made the
// VSM filter ~25 % slower).
SL_ROW_CLONES void interleave_row(const float* a, const float* b, int w, float* out) {
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

#if defined(__x86_64__)
// rows[0][x] + rows[1][x] + … + rows[K − 1][x], added in row order (mean_out_k's sum), for one
// texel and for 8 (AVX-512): the output kernels' sums of K filtered rows.
template <int K>
inline double sum_rows(const double* const* rows, int x) {
  double a = rows[0][x];
  for (int j = 1; j < K; ++j) a += rows[j][x];
  return a;
}
// One texel of the fused output rows, for their heads and tails (the vector steps' operations):
// VSM's (mean, variance) from rows[0 .. K − 1] and rows[K .. 2K − 1].
template <int K>
inline void vsm_out_texel(const double* const* rows, int x, double inv, float* out) {
  const double a = sum_rows<K>(rows, x) * inv, b = sum_rows<K>(rows + K, x) * inv;
  out[2 * x] = float(a);
  out[2 * x + 1] = float(positive_part(b - a * a));
}
template <int K>
SL_TARGET("avx512f") inline __m512d sum_rows8(const double* const* rows, int x) {
  __m512d a = _mm512_loadu_pd(rows[0] + x);
  for (int j = 1; j < K; ++j) a = _mm512_add_pd(a, _mm512_loadu_pd(rows[j] + x));
  return a;
}

// VSM's (and EVSM's two-value) output row straight into the interleaved plane: vsm_out_k's sums,
// products and positive part for both planes (rows[0 .. K − 1] the first moments', rows[K ..
// 2K − 1] the second's), 8 texels at a time, zipped to (mean, variance) per texel and stored as
// one 64-byte line per 8 texels with ordinary stores (VSM keeps its map in the caches for the
// lookup: docs/performance.md). What vsm_out_k into scratch and interleave_row did in
// two passes, in one; the same bits (MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoops-
// BitForBit). Texels before the first line and after the last whole 8 go one by one.
template <int K>
SL_TARGET("avx512f") void vsm_out_interleaved_avx512(const double* const* rows,
                                                     int w, double inv,
                                                     float* out) {
  const int head = texels_to_line(out, 2, w);
  int x = 0;
  for (; x < head; ++x) vsm_out_texel<K>(rows, x, inv, out);
  const __m512d vinv = _mm512_set1_pd(inv), zero = _mm512_setzero_pd();
  for (; x + 8 <= w; x += 8) {
    const __m512d a = _mm512_mul_pd(sum_rows8<K>(rows, x), vinv);
    const __m512d b = _mm512_mul_pd(sum_rows8<K>(rows + K, x), vinv);
    const __m512d v = _mm512_sub_pd(b, _mm512_mul_pd(a, a));
    // positive_part: v where v > 0, else +0 (a NaN too).
    const __m512d pv = _mm512_mask_mov_pd(zero, _mm512_cmp_pd_mask(v, zero, _CMP_GT_OQ), v);
    const __m256 mean = _mm512_maskz_cvtpd_ps(0xFF, a), var = _mm512_maskz_cvtpd_ps(0xFF, pv);
    const __m256 lo = _mm256_unpacklo_ps(mean, var);  // texels 0 1 | 4 5
    const __m256 hi = _mm256_unpackhi_ps(mean, var);  // texels 2 3 | 6 7
    _mm256_storeu_ps(out + 2 * x, _mm256_permute2f128_ps(lo, hi, 0x20));
    _mm256_storeu_ps(out + 2 * x + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
  }
  for (; x < w; ++x) vsm_out_texel<K>(rows, x, inv, out);
}

// The same in AVX2, 4 texels (one 32-byte store) per step: the AVX2-only machines' fused row
// (before it, their rows went through vsm_out_k into scratch and interleave_row, two passes).
template <int K>
SL_TARGET("avx2") void vsm_out_interleaved_avx2(const double* const* rows, int w,
                                                double inv, float* out) {
  const int head = texels_to_line(out, 2, w);
  int x = 0;
  for (; x < head; ++x) vsm_out_texel<K>(rows, x, inv, out);
  const double* r[2 * K];
  for (int j = 0; j < 2 * K; ++j) r[j] = rows[j];
  const __m256d vinv = _mm256_set1_pd(inv), zero = _mm256_setzero_pd();
  for (; x + 4 <= w; x += 4) {
    __m256d a = _mm256_loadu_pd(r[0] + x), b = _mm256_loadu_pd(r[K] + x);
    for (int j = 1; j < K; ++j) {
      a = _mm256_add_pd(a, _mm256_loadu_pd(r[j] + x));
      b = _mm256_add_pd(b, _mm256_loadu_pd(r[K + j] + x));
    }
    a = _mm256_mul_pd(a, vinv);
    b = _mm256_mul_pd(b, vinv);
    const __m256d v = _mm256_sub_pd(b, _mm256_mul_pd(a, a));
    // positive_part: v where v > 0, else +0 (a NaN too).
    const __m256d pv = _mm256_and_pd(v, _mm256_cmp_pd(v, zero, _CMP_GT_OQ));
    const __m128 mean = _mm256_cvtpd_ps(a), var = _mm256_cvtpd_ps(pv);
    // texels 0 1 in the low half, 2 3 in the high one.
    _mm256_storeu_ps(out + 2 * x,
                     _mm256_set_m128(_mm_unpackhi_ps(mean, var), _mm_unpacklo_ps(mean, var)));
  }
  for (; x < w; ++x) vsm_out_texel<K>(rows, x, inv, out);
}
#endif

}  // namespace

namespace {

// Where filtered means and variances go: texel i's at mean[stride·i] and var[stride·i]; stride
// 1 for two planes, 2 for one interleaved plane (var = mean + 1).
struct MeanVarOut {
  float* mean;
  float* var;
  int stride;
};

// Row y's mean and variance floats of the span's columns through write(mean_row, var_row):
// straight into the planes, or (stride 2 or 4) into `scratch` (2·n floats) and then interleaved
// (stride 4: into two of each texel's four slots; EVSM4 writes its two warps' pairs side by
// side). Stored with ordinary stores: streaming VSM's 8 B per texel (core/stream_copy.h) made
// its filter 0.3 ms faster and its lookup 0.35 ms slower (the lookup then reads what the caches
// would have held), so it would only move time between the phases.
template <class Write>
void write_mean_var(const MeanVarOut& o, int w, int y, const SpanCols& s, float* scratch,
                    const Write& write) {
  const size_t at = (size_t(y) * size_t(w) + size_t(s.x0)) * size_t(o.stride);
  const int n = s.n;
  if (o.stride == 1) {
    write(o.mean + at, o.var + at);
    return;
  }
  write(scratch, scratch + n);
  if (o.stride == 2) {
    interleave_row(scratch, scratch + n, n, o.mean + at);
    return;
  }
  float* const row = o.mean + at;
  for (int x = 0; x < n; ++x) {
    row[size_t(o.stride) * size_t(x)] = scratch[x];
    row[size_t(o.stride) * size_t(x) + 1] = scratch[size_t(n) + size_t(x)];
  }
}

// Row y's filtered mean and variance from its window of K rows of each plane's horizontal sums
// (vsm_out_k's operations): straight into the interleaved plane by vsm_out_interleaved_avx512
// or _avx2 where the plane interleaves two values and that ISA is in use (isa), else through
// write_mean_var.
template <int K>
void vsm_out_row(const MeanVarOut& o, int w, int y, const SpanCols& s, const double* const* win,
                 double* scratch, double inv, Isa isa) {
#if defined(__x86_64__)
  if (o.stride == 2 && isa != Isa::scalar) {
    float* const row = o.mean + 2 * (size_t(y) * size_t(w) + size_t(s.x0));
    if (isa == Isa::avx512)
      vsm_out_interleaved_avx512<K>(win, s.n, inv, row);
    else
      vsm_out_interleaved_avx2<K>(win, s.n, inv, row);
    return;
  }
#else
  (void)isa;
#endif
  write_mean_var(o, w, y, s, reinterpret_cast<float*>(scratch),
                 [&](float* m, float* v) { vsm_out_k<K>(win, s.n, inv, m, v); });
}

// Filtered mean and centred variance of a two-plane row maker: make_row(y, cols, ext) fills
// plane 0 at ext and plane 1 at ext + (w + k − 1) with the span's extended row (cols.n + k − 1
// values: SpanCols).
// With `fixed` and a compiled width, the fixed-width kernels; else the runtime-k loops (their
// oracle): the same additions in the same order either way.
template <class MakeRow>
void box_mean_variance(int w, int h, int k, bool fixed, const FaceTiles* tiles, const float* src,
                       const MakeRow& make_row, const MeanVarOut& o) {
  const size_t ew = size_t(w) + size_t(k) - 1;
  const double inv = 1.0 / double(k * k);
#if defined(__x86_64__)
  const Isa isa = exp_path(true);  // vsm_out_interleaved_avx512 / _avx2 for stride 2
#endif
  if (fixed && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        fused_box(
            w, h, k, 2, tiles, src,
            [&](int y, const SpanCols& s, double* const* dst, double* ext) {
              make_row(y, s, ext);
              hsum_k<K>(ext, s.n, dst[0]);
              hsum_k<K>(ext + ew, s.n, dst[1]);
            },
            [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
              vsm_out_row<K>(o, w, y, s, win, scratch, inv, isa);
            });
      }))
    return;
  fused_box(
      w, h, k, 2, tiles, src,
      [&](int y, const SpanCols& s, double* const* dst, double* ext) {
        make_row(y, s, ext);
        hsum_row(ext, s.n, k, dst[0]);
        hsum_row(ext + ew, s.n, k, dst[1]);
      },
      [&](int y, const SpanCols& s, const double* const* win, double* out) {
        vsum_rows(win, s.n, k, inv, out);
        vsum_rows(win + k, s.n, k, inv, out + w);
        // out holds the two summed rows (2·w doubles); the floats go after them in the
        // planes' scratch only when interleaving, so use a row of their own.
        float* const tmp = reinterpret_cast<float*>(out + 2 * size_t(w));
        write_mean_var(o, w, y, s, tmp, [&](float* m, float* v) {
          mean_variance_row(out, out + w, s.n, m, v);
        });
      });
}

// VSM's and EVSM's k = 3 filter (techniques/filters/moments_common/centred_window3.h: one centred 9-tap float window
// per texel): per band of 32 output rows and span of needed columns (as fused_box walks them),
// a ring of the three extended input rows make_row(y, cols, in) writes (cols.in_n floats at
// `in`, clamped at the span's ends here), each made once per band and span, the next one's
// input prefetched (fused_box says why); the output rows by `isa`'s centred_window3 row.
template <class MakeRow>
void centred3_box(int w, int h, const FaceTiles* tiles, const float* src, Isa isa,
                  const MeanVarOut& o, const MakeRow& make_row) {
  const int bands = (h + kTexelTile - 1) / kTexelTile;
  const CentredWindow3RowFn window_row = centred_window3_kernels(isa).row;
  parallel_for_chunks(size_t(bands), 1, [&](size_t b0, size_t b1) {
    const size_t row_len = size_t(w) + 2;
    const std::unique_ptr<float[]> ring(new float[3 * row_len]);
    auto slot = [&](int y) { return ring.get() + size_t(y % 3) * row_len; };
    std::vector<TexelSpan> spans;
    for (size_t band = b0; band < b1; ++band) {
      tile_spans(tiles, int(band), w, spans);
      const int y0 = int(band) * kTexelTile, y1 = std::min(h, y0 + kTexelTile);
      for (const TexelSpan& span : spans) {
        const SpanCols cols = span_cols(span, w, 1);
        int next = std::max(0, y0 - 1);  // the first input row not made yet
        for (int y = y0; y < y1; ++y) {
          const int below = std::min(h - 1, y + 1);
          for (; next <= below; ++next) {
            if (next + 1 < h)
              prefetch_bytes(src + size_t(next + 1) * size_t(w) + size_t(cols.in0),
                             size_t(cols.in_n) * sizeof(float));
            float* const row = slot(next);
            make_row(next, cols, row + cols.lead);
            extend_span(row, cols, 3);
          }
          const size_t at = (size_t(y) * size_t(w) + size_t(cols.x0)) * size_t(o.stride);
          window_row(slot(std::max(0, y - 1)), slot(y), slot(below), cols.n, o.mean + at,
                     o.var + at, o.stride);
        }
      }
    }
  });
}

// The fixed-width box of a float row's two moments: make_row(y, span, in) writes the span's
// span.in_n input floats at `in` (finite distances for VSM, EVSM's warp), then the row is
// clamped at its ends and hsum_moments_k forms each value and its square in double inside the
// horizontal sums; the output rows by vsm_out_row (its fused kernels per `isa`). False, having
// done nothing, for a width without a fixed kernel.
template <class MakeRow>
bool float_moments_fixed(int w, int h, int k, const FaceTiles* tiles, const float* src,
                         Isa isa, const MeanVarOut& o, const MakeRow& make_row) {
  const double inv = 1.0 / double(k * k);
  return with_fixed_width(k, [&](auto kc) {
    constexpr int K = decltype(kc)::value;
    fused_box(
        w, h, k, 2, tiles, src,
        [&](int y, const SpanCols& s, double* const* dst, double* ext) {
          float* const ext_f = reinterpret_cast<float*>(ext);
          make_row(y, s, ext_f + s.lead);
          extend_span(ext_f, s, k);
          hsum_moments_k<K>(ext_f, s.n, dst[0], dst[1]);
        },
        [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
          vsm_out_row<K>(o, w, y, s, win, scratch, inv, isa);
        });
  });
}

void moments_double(const float* dist, int w, int h, int k, bool slope_term, bool fixed_kernels,
                    const FaceTiles* tiles, const MeanVarOut& o) {
  const int r = k / 2;
  const size_t ew = size_t(w) + size_t(k) - 1;
  // k = 3 without the slope term: the centred float window, the oracle with its scalar kernel.
  if (k == 3 && !slope_term) {
    centred3_box(w, h, tiles, dist, exp_path(fixed_kernels), o,
                 [&](int y, const SpanCols& s, float* in) {
                   finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, in);
                 });
    return;
  }
  // Without the slope term, d² is formed inside the horizontal sums from the float row.
  if (fixed_kernels && !slope_term &&
      float_moments_fixed(w, h, k, tiles, dist, exp_path(true), o,
                          [&](int y, const SpanCols& s, float* in) {
                            finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, in);
                          }))
    return;
  auto at = [&](int x, int y) {
    return double(finite_dist(dist[size_t(std::clamp(y, 0, h - 1)) * size_t(w) +
                                   size_t(std::clamp(x, 0, w - 1))]));
  };
  box_mean_variance(
      w, h, k, fixed_kernels, tiles, dist,
      [&](int y, const SpanCols& s, double* ext) {
        if (!slope_term) {
          moment_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead,
                     ext + ew + size_t(s.lead));
          extend_span(ext, s, k);
          extend_span(ext + ew, s, k);
          return;
        }
        // raw_moments' values of row y's columns [x0 − r, x0 + n + r), clamped to the image.
        for (int x = s.x0 - r; x < s.x0 + s.n + r; ++x) {
          const double d = at(x, y);
          double m2 = d * d;
          const int xc = std::clamp(x, 0, w - 1);
          const double dx = min_diff(at(xc - 1, y), d, at(xc + 1, y));
          const double dy = min_diff(at(xc, y - 1), d, at(xc, y + 1));
          m2 += double(0.25 * (dx * dx + dy * dy));
          ext[size_t(x - (s.x0 - r))] = d;
          ext[ew + size_t(x - (s.x0 - r))] = m2;
        }
      },
      o);
}

// Two planes of w × h floats.
MeanVarOut planes_out(int w, int h, std::vector<float>& mean, std::vector<float>& variance) {
  const size_t n = size_t(w) * size_t(h);
  mean.resize(n);
  variance.resize(n);
  return {mean.data(), variance.data(), 1};
}

// One interleaved plane of 2 × w × h floats.
MeanVarOut interleaved_out(int w, int h, std::vector<float>& mv) {
  mv.resize(2 * size_t(w) * size_t(h));
  return {mv.data(), mv.data() + 1, 2};
}

}  // namespace

void filter_moments_double(const float* dist, int w, int h, int k, bool slope_term,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, true, tiles, planes_out(w, h, mean, variance));
}

void filter_moments_double_oracle(const float* dist, int w, int h, int k, bool slope_term,
                                  std::vector<float>& mean, std::vector<float>& variance,
                                  const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, false, tiles, planes_out(w, h, mean, variance));
}

void filter_moments_double_interleaved(const float* dist, int w, int h, int k, bool slope_term,
                                       std::vector<float>& mean_variance, const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, true, tiles, interleaved_out(w, h, mean_variance));
}

namespace {

void warped_moments(const float* dist, int w, int h, int k, double c, double sign,
                    bool fixed_kernels, const FaceTiles* tiles, const MeanVarOut& o) {
  const size_t ew = size_t(w) + size_t(k) - 1;
  // k = 3: the centred float window of the float warp, the oracle with the scalar warp and
  // window kernels.
  if (k == 3) {
    const Isa path = exp_path(fixed_kernels);
    centred3_box(w, h, tiles, dist, path, o,
                 [&](int y, const SpanCols& s, float* in) {
                   warp_row_f(path, dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c,
                              sign, in);
                 });
    return;
  }
  // Fixed widths: the warp as floats, its moments formed in the horizontal sums (VSM's
  // fixed path); the runtime-k oracle keeps the two double rows.
  if (fixed_kernels) {
    const Isa path = exp_path(true);
    if (float_moments_fixed(w, h, k, tiles, dist, path, o,
                            [&](int y, const SpanCols& s, float* in) {
                              warp_row_f(path, dist + size_t(y) * size_t(w) + size_t(s.in0),
                                         s.in_n, c, sign, in);
                            }))
      return;
  }
  box_mean_variance(
      w, h, k, fixed_kernels, tiles, dist,
      [&](int y, const SpanCols& s, double* ext) {
        warped_row_scalar(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c, sign,
                          ext + s.lead, ext + ew + size_t(s.lead));
        extend_span(ext, s, k);
        extend_span(ext + ew, s, k);
      },
      o);
}

}  // namespace

void filter_warped_moments(const float* dist, int w, int h, int k, double c, double sign,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles) {
  warped_moments(dist, w, h, k, c, sign, true, tiles, planes_out(w, h, mean, variance));
}

void filter_warped_moments_interleaved(const float* dist, int w, int h, int k, double c,
                                       double sign, int stride, int first,
                                       std::vector<float>& out, const FaceTiles* tiles) {
  SL_CHECK((stride == 2 && first == 0) || (stride == 4 && (first == 0 || first == 2)));
  const size_t n = size_t(w) * size_t(h) * size_t(stride);
  if (out.size() != n) out.resize(n);
  float* const base = out.data() + first;
  warped_moments(dist, w, h, k, c, sign, true, tiles, {base, base + 1, stride});
}

void filter_warped_moments_oracle(const float* dist, int w, int h, int k, double c,
                                  double sign, std::vector<float>& mean,
                                  std::vector<float>& variance, const FaceTiles* tiles) {
  warped_moments(dist, w, h, k, c, sign, false, tiles, planes_out(w, h, mean, variance));
}

void filter_moments_fp32(const float* dist, int w, int h, int k, bool slope_term,
                         std::vector<float>& m1, std::vector<float>& m2) {
  std::vector<float> in[2], tmp[2], out[2];
  raw_moments<float>(dist, w, h, slope_term, in[0], in[1]);
  box_mean<float, 2>(in, w, h, k, tmp, out);
  m1.swap(out[0]);
  m2.swap(out[1]);
}

void filter_max(const float* dist, int w, int h, int k, std::vector<float>& out,
                FilterScratch& scratch) {
  const int r = k / 2;
  const size_t n = size_t(w) * size_t(h);
  std::vector<float>& tmp = scratch.tmp_f;
  tmp.resize(n);
  out.resize(n);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        float m = 0.0f;
        for (int i = -r; i <= r; ++i)
          m = std::max(m, finite_dist(dist[y * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))]));
        tmp[y * size_t(w) + size_t(x)] = m;
      }
  });
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        float m = 0.0f;
        for (int j = -r; j <= r; ++j)
          m = std::max(m, tmp[size_t(std::clamp(int(y) + j, 0, h - 1)) * size_t(w) + size_t(x)]);
        out[y * size_t(w) + size_t(x)] = m;
      }
  });
}

}  // namespace shadowlab
