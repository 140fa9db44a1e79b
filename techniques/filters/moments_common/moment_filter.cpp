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
void write_mean_var(const MomentRowKernels& kr, const MeanVarOut& o, int w, int y,
                    const SpanCols& s, float* scratch, const Write& write) {
  const size_t at = (size_t(y) * size_t(w) + size_t(s.x0)) * size_t(o.stride);
  const int n = s.n;
  if (o.stride == 1) {
    write(o.mean + at, o.var + at);
    return;
  }
  write(scratch, scratch + n);
  if (o.stride == 2) {
    kr.interleave_row(scratch, scratch + n, n, o.mean + at);
    return;
  }
  float* const row = o.mean + at;
  for (int x = 0; x < n; ++x) {
    row[size_t(o.stride) * size_t(x)] = scratch[x];
    row[size_t(o.stride) * size_t(x) + 1] = scratch[size_t(n) + size_t(x)];
  }
}

// Row y's filtered mean and variance from its window of K rows of each plane's horizontal sums
// (vsm_out_k's operations): straight into the interleaved plane by the table's
// vsm_out_interleaved where the plane interleaves two values and the table has one, else through
// write_mean_var.
template <int K>
void vsm_out_row(const MomentRowKernels& kr, const MeanVarOut& o, int w, int y, const SpanCols& s,
                 const double* const* win, double* scratch, double inv) {
  constexpr int slot = moment_width_slot(K);
  if (o.stride == 2 && kr.vsm_out_interleaved[slot]) {
    float* const row = o.mean + 2 * (size_t(y) * size_t(w) + size_t(s.x0));
    kr.vsm_out_interleaved[slot](win, s.n, inv, row);
    return;
  }
  write_mean_var(kr, o, w, y, s, reinterpret_cast<float*>(scratch),
                 [&](float* m, float* v) { kr.vsm_out_k[slot](win, s.n, inv, m, v); });
}

// Filtered mean and centred variance of a two-plane row maker: make_row(y, cols, ext) fills
// plane 0 at ext and plane 1 at ext + (w + k − 1) with the span's extended row (cols.n + k − 1
// values: SpanCols).
// With `fixed` and a compiled width, the fixed-width kernels; else the runtime-k loops (their
// oracle): the same additions in the same order either way.
template <class MakeRow>
void box_mean_variance(int w, int h, int k, bool fixed, const FaceTiles* tiles, const float* src,
                       const MakeRow& make_row, const MeanVarOut& o) {
  const MomentRowKernels& kr = row_kernels(fixed);
  const size_t ew = size_t(w) + size_t(k) - 1;
  const double inv = 1.0 / double(k * k);
  if (fixed && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        fused_box(
            w, h, k, 2, tiles, src,
            [&](int y, const SpanCols& s, double* const* dst, double* ext) {
              make_row(y, s, ext);
              kr.hsum_k[moment_width_slot(K)](ext, s.n, dst[0]);
              kr.hsum_k[moment_width_slot(K)](ext + ew, s.n, dst[1]);
            },
            [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
              vsm_out_row<K>(kr, o, w, y, s, win, scratch, inv);
            });
      }))
    return;
  fused_box(
      w, h, k, 2, tiles, src,
      [&](int y, const SpanCols& s, double* const* dst, double* ext) {
        make_row(y, s, ext);
        kr.hsum_row_d(ext, s.n, k, dst[0]);
        kr.hsum_row_d(ext + ew, s.n, k, dst[1]);
      },
      [&](int y, const SpanCols& s, const double* const* win, double* out) {
        kr.vsum_rows_d(win, s.n, k, inv, out);
        kr.vsum_rows_d(win + k, s.n, k, inv, out + w);
        // out holds the two summed rows (2·w doubles); the floats go after them in the
        // planes' scratch only when interleaving, so use a row of their own.
        float* const tmp = reinterpret_cast<float*>(out + 2 * size_t(w));
        write_mean_var(kr, o, w, y, s, tmp, [&](float* m, float* v) {
          kr.mean_variance_row(out, out + w, s.n, m, v);
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
// horizontal sums; the output rows by vsm_out_row (the table's fused rows). False, having done
// nothing, for a width without a fixed kernel.
template <class MakeRow>
bool float_moments_fixed(int w, int h, int k, const FaceTiles* tiles, const float* src,
                         const MomentRowKernels& kr, const MeanVarOut& o,
                         const MakeRow& make_row) {
  const double inv = 1.0 / double(k * k);
  return with_fixed_width(k, [&](auto kc) {
    constexpr int K = decltype(kc)::value;
    fused_box(
        w, h, k, 2, tiles, src,
        [&](int y, const SpanCols& s, double* const* dst, double* ext) {
          float* const ext_f = reinterpret_cast<float*>(ext);
          make_row(y, s, ext_f + s.lead);
          extend_span(ext_f, s, k);
          kr.hsum_moments_k[moment_width_slot(K)](ext_f, s.n, dst[0], dst[1]);
        },
        [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
          vsm_out_row<K>(kr, o, w, y, s, win, scratch, inv);
        });
  });
}

void moments_double(const float* dist, int w, int h, int k, bool slope_term, bool fixed_kernels,
                    const FaceTiles* tiles, const MeanVarOut& o) {
  const int r = k / 2;
  const size_t ew = size_t(w) + size_t(k) - 1;
  const MomentRowKernels& kr = row_kernels(fixed_kernels);
  // k = 3 without the slope term: the centred float window, the oracle with its scalar kernel.
  if (k == 3 && !slope_term) {
    centred3_box(w, h, tiles, dist, kr.isa, o,
                 [&](int y, const SpanCols& s, float* in) {
                   kr.finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, in);
                 });
    return;
  }
  // Without the slope term, d² is formed inside the horizontal sums from the float row.
  if (fixed_kernels && !slope_term &&
      float_moments_fixed(w, h, k, tiles, dist, kr, o,
                          [&](int y, const SpanCols& s, float* in) {
                            kr.finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0),
                                          s.in_n, in);
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
          kr.moment_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead,
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
  const MomentRowKernels& kr = row_kernels(fixed_kernels);
  // k = 3: the centred float window of the float warp, the oracle with the scalar warp and
  // window kernels.
  if (k == 3) {
    centred3_box(w, h, tiles, dist, kr.isa, o,
                 [&](int y, const SpanCols& s, float* in) {
                   kr.warp_row_f(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c,
                                 sign, in);
                 });
    return;
  }
  // Fixed widths: the warp as floats, its moments formed in the horizontal sums (VSM's
  // fixed path); the runtime-k oracle keeps the two double rows.
  if (fixed_kernels) {
    if (float_moments_fixed(w, h, k, tiles, dist, kr, o,
                            [&](int y, const SpanCols& s, float* in) {
                              kr.warp_row_f(dist + size_t(y) * size_t(w) + size_t(s.in0),
                                            s.in_n, c, sign, in);
                            }))
      return;
  }
  box_mean_variance(
      w, h, k, fixed_kernels, tiles, dist,
      [&](int y, const SpanCols& s, double* ext) {
        kr.warped_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c, sign,
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
