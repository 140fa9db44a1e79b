// MSM's filter (techniques/filters/moments_common/moment_filter.h): the four power moments d, d², d³, d⁴ box-filtered
// in float (the rows, and the writers of the interleaved map's 64-byte lines, are
// techniques/filters/moments_common/moment_rows.h's).
#include "techniques/filters/moments_common/moment_filter.h"

#include "techniques/filters/moments_common/moment_box.h"

namespace shadowlab {
namespace {

// Plane c's filtered row y (a span's columns) goes to row_of(c, y, span, tmp): a row of out[c],
// or (interleaved given) the c-th of four span.n-float rows in tmp, which finish(y, span, tmp)
// then interleaves into row y. The sums are in float (moment_filter.h says why): the powers as
// power_row forms them, each horizontal sum from 0 in window order, the vertical sums in row
// order, then × 1/k² (a float), the same operations on every path.
void power_moments(const float* dist, int w, int h, int k, bool fixed_kernels,
                   const FaceTiles* tiles, std::vector<float>* out,
                   std::vector<float>* interleaved) {
  const size_t n = size_t(w) * size_t(h);
  if (interleaved)
    interleaved->resize(4 * n);
  else
    for (int c = 0; c < 4; ++c) out[c].resize(n);
  const size_t ew = size_t(w) + size_t(k) - 1;
  const float inv = 1.0f / float(k * k);
  const MomentRowKernels& kr = row_kernels(fixed_kernels);
  auto make_row = [&](int y, const SpanCols& s, float* ext) {
    kr.power_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ew, ext + s.lead);
    for (int c = 0; c < 4; ++c) extend_span(ext + size_t(c) * ew, s, k);
  };
  // Plane c's row y: in the plane, or (interleaving) in tmp's c-th row of s.n floats.
  auto row_of = [&](int c, int y, const SpanCols& s, float* tmp) {
    return interleaved ? tmp + size_t(c) * size_t(s.n)
                       : out[c].data() + size_t(y) * size_t(w) + size_t(s.x0);
  };
  // The interleaved row is made in tmp after the four planes' rows, then streamed into the map
  // (core/stream_copy.h): 16 B per texel is beyond the caches (~35 MB on the default scene's
  // cube), and not reading each line before writing it made the filter 0.55 ms faster and the
  // lookup 0.2 ms slower (AMD EPYC: docs/performance.md).
  const StreamCopy copy = stream_copy_kernel();
  // The fused rows that write the interleaved map straight from registers (none in the scalar
  // table, whose rows go through tmp, interleave4_row and the stream copy).
  const bool fused = interleaved && kr.msm_hsum_out[0] != nullptr;
  auto finish = [&](int y, const SpanCols& s, float* tmp) {
    if (!interleaved) return;
    float* const row = tmp + 4 * size_t(s.n);
    kr.interleave4_row(tmp, s.n, row);
    copy(row, 4 * size_t(s.n), interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0)));
  };
  // Row y's finite distances over the span's input columns, extended to its window (ext).
  auto finite_ext = [&](int y, const SpanCols& s, float* ext) {
    kr.finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead);
    extend_span(ext, s, k);
  };
  if (fixed_kernels && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        constexpr int slot = moment_width_slot(K);
        fused_box<float>(
            w, h, k, 4, tiles, dist,
            [&](int y, const SpanCols& s, float* const* dst, float* ext) {
              finite_ext(y, s, ext);
              kr.hsum_powers_k[slot](ext, s.n, dst[0], dst[1], dst[2], dst[3]);
            },
            [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
              if (fused) {
                float* const row =
                    interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
                kr.msm_out_interleaved[slot](win, s.n, inv, row);
                return;
              }
              // tmp: 8·n of its 10·w floats.
              for (int c = 0; c < 4; ++c)
                kr.mean_out_k[slot](win + c * K, s.n, inv, row_of(c, y, s, tmp));
              finish(y, s, tmp);
            },
            [&](int y, int row, const SpanCols& s, float* const* dst, const float* const* win,
                float* ext) {
              if (!fused) return false;
              finite_ext(row, s, ext);
              float* const out_row =
                  interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
              // The pages output row y + 2 will be streamed into (core/prefetch.h): without the
              // hint the cube filter took ~40 % longer on the default scene.
              if (y + 2 < h) prefetch_pages(out_row + 8 * size_t(w), 16 * size_t(s.n));
              kr.msm_hsum_out[slot](ext, dst, win, s.n, inv, out_row);
              return true;
            });
      }))
    return;
  fused_box<float>(
      w, h, k, 4, tiles, dist,
      [&](int y, const SpanCols& s, float* const* dst, float* ext) {
        make_row(y, s, ext);
        for (int c = 0; c < 4; ++c) kr.hsum_row_f(ext + size_t(c) * ew, s.n, k, dst[c]);
      },
      [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
        // tmp: 4·n floats of plane rows and 4·n of the interleaved row (of its 10·w floats).
        for (int c = 0; c < 4; ++c) kr.vsum_rows_f(win + c * k, s.n, k, inv, row_of(c, y, s, tmp));
        finish(y, s, tmp);
      });
}

}  // namespace

void filter_power_moments(const float* dist, int w, int h, int k, std::vector<float>* out,
                          const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, out, nullptr);
}

void filter_power_moments_interleaved(const float* dist, int w, int h, int k,
                                      std::vector<float>& moments, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, nullptr, &moments);
}

void filter_power_moments_oracle(const float* dist, int w, int h, int k,
                                 std::vector<float>* out, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, false, tiles, out, nullptr);
}

}  // namespace shadowlab
