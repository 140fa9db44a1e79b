// ESM's filter (techniques/filters/moments_common/moment_filter.h): the box filter of e^(c·(d − d_min)) in double and
// its logarithm, c·d_min + ln(mean), stored as float (the rows: techniques/filters/moments_common/moment_rows.h).
#include "techniques/filters/moments_common/moment_filter.h"

#include "techniques/filters/moments_common/moment_box.h"

namespace shadowlab {
namespace {

void esm_log(const float* dist, int w, int h, int k, double c, bool fixed_kernels,
             const FaceTiles* tiles, const float* face_min, std::vector<float>& out) {
  const size_t n = size_t(w) * size_t(h);
  out.resize(n);
  // The tiles whose inputs' range allows it go through the float path (techniques/
  // esm_float_tiles.h); the rest, and every tile of a box wider than it takes, below.
  FaceTiles rest;
  if (k <= kEsmFloatMaxWidth) {
    if (esm_float_tiles(dist, w, h, k, c, fixed_kernels, tiles, out.data(), rest) == 0) return;
    tiles = &rest;
  }
  // The image's smallest finite distance (1 when none is smaller): from the caller, or a
  // fixed-order reduction over per-row minima.
  double d_min = 1.0;
  const MomentRowKernels& kr = row_kernels(fixed_kernels);
  if (face_min) {
    d_min = *face_min < 1.0f ? double(*face_min) : 1.0;
  } else {
    std::vector<float> row_min(static_cast<size_t>(h));
    parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
      for (size_t y = b; y < e; ++y) row_min[y] = kr.row_min_dist(dist + y * size_t(w), w);
    });
    for (float m : row_min) d_min = std::min(d_min, double(m));
  }
  const double inv = 1.0 / double(k * k);
  auto exp_row = [&](int y, const SpanCols& s, double* ext) {
    kr.esm_exp_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c, d_min,
                   ext + s.lead);
    extend_span(ext, s, k);
  };
  auto out_at = [&](int y, const SpanCols& s) {
    return out.data() + size_t(y) * size_t(w) + size_t(s.x0);
  };
  const bool fixed = fixed_kernels && with_fixed_width(k, [&](auto kc) {
    constexpr int K = decltype(kc)::value;
    fused_box(
        w, h, k, 1, tiles, dist,
        [&](int y, const SpanCols& s, double* const* dst, double* ext) {
          exp_row(y, s, ext);
          kr.hsum_k[moment_width_slot(K)](ext, s.n, dst[0]);
        },
        [&](int y, const SpanCols& s, const double* const* win, double*) {
          kr.esm_out_k[moment_width_slot(K)](win, s.n, inv, c, d_min, out_at(y, s));
        });
  });
  if (fixed) return;
  fused_box(
      w, h, k, 1, tiles, dist,
      [&](int y, const SpanCols& s, double* const* dst, double* ext) {
        exp_row(y, s, ext);
        kr.hsum_row_d(ext, s.n, k, dst[0]);
      },
      [&](int y, const SpanCols& s, const double* const* win, double* filtered) {
        kr.vsum_rows_d(win, s.n, k, inv, filtered);
        kr.esm_log_row(filtered, s.n, c, d_min, out_at(y, s));
      });
}

}  // namespace

void filter_esm_log(const float* dist, int w, int h, int k, double c, std::vector<float>& out,
                    const FaceTiles* tiles, const float* face_min) {
  esm_log(dist, w, h, k, c, true, tiles, face_min, out);
}

void filter_esm_log_oracle(const float* dist, int w, int h, int k, double c,
                           std::vector<float>& out, const FaceTiles* tiles) {
  esm_log(dist, w, h, k, c, false, tiles, nullptr, out);
}


}  // namespace shadowlab
