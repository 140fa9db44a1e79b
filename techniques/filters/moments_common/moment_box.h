#pragma once
// The shared machinery of the moment filters (techniques/filters/moments_common/moment_filter.h), included only by
// their files: moment_filter.cpp (VSM's and EVSM's mean and variance), moment_filter_msm.cpp
// (MSM's four power moments and their line writers) and moment_filter_esm.cpp (ESM's log-space
// box). Here: the finite-distance helpers, the choice of row kernel table, the span columns, the
// fused separable box driver and the compiled widths; the row kernels themselves are a kernel
// family (techniques/filters/moments_common/moment_rows.h).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/isa.h"
#include "core/prefetch.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/stream_copy.h"
#include "techniques/filters/moments_common/centred_window3.h"
#include "techniques/filters/esm/esm_float_tiles.h"
#include "techniques/filters/moments_common/moment_rows.h"
#include "techniques/pipeline/texel_tiles.h"

namespace shadowlab {
namespace {

// Distance with "nothing seen" as the light's range: d < 1 ? d : 1.
inline float finite_dist(float d) { return d < 1.0f ? d : 1.0f; }

// Smaller-magnitude one-sided difference of a row/column sample (neighbours clamped).
inline double min_diff(double prev, double here, double next) {
  const double a = here - prev, b = next - here;
  return std::fabs(a) <= std::fabs(b) ? a : b;
}

// A filter's row kernels (techniques/filters/moments_common/moment_rows.h), chosen once per filter: the table of
// process_isa(); the oracles (fixed_kernels false) take the scalar table, so the tests'
// comparisons of the two also compare the tables bit for bit.
inline const MomentRowKernels& row_kernels(bool fast) {
  return moment_row_kernels(fast ? process_isa() : Isa::scalar);
}

// Output columns [x0, x0 + n) of a row and the input columns their k-wide windows read:
// [in0, in0 + in_n) of the image (clipped to it), placed at ext[lead ..] of the extended row,
// whose positions before lead and from lead + in_n on repeat the image's edge texels (clamp to
// edge). The whole row: x0 = 0, n = w, in0 = 0, in_n = w, lead = k/2.
struct SpanCols {
  int x0, n, in0, in_n, lead;
};

inline SpanCols span_cols(const TexelSpan& s, int w, int r) {
  SpanCols c;
  c.x0 = s.x0;
  c.n = s.x1 - s.x0;
  c.in0 = std::max(0, s.x0 - r);
  c.in_n = std::min(w, s.x1 + r) - c.in0;
  c.lead = c.in0 - (s.x0 - r);
  return c;
}

// Fills the clamped positions of a span's extended row (n + k − 1 values) from its edge values.
template <class T>
inline void extend_span(T* ext, const SpanCols& c, int k) {
  for (int i = 0; i < c.lead; ++i) ext[i] = ext[c.lead];
  const int end = c.lead + c.in_n, total = c.n + k - 1;
  for (int i = end; i < total; ++i) ext[i] = ext[end - 1];
}

// The fused separable box over `planes` planes of sums of type T (double; MSM's float), as a ring
// of k horizontal-sum rows per span of output columns in each band of 32 output rows
// (kTexelTile: one span over the whole width without `tiles`, else the needed tiles' runs,
// tile_spans): hrow(y, span, dst, ext) writes input row y's horizontal sums over the span's
// columns (dst[c]: span.n values of plane c; ext: scratch of planes × (w + k − 1) values);
// out_row(y, span, window, out) receives, plane after plane, the k rows' pointers of output row
// y's vertical window (rows clamped to the image) in top-to-bottom order, and scratch of
// (planes + 1) × w doubles' worth of bytes. Each input row's sums are
// computed once per band and span (plus k − 1 rows shared with the next band) and stay in cache.
// `src` (w floats per row, the distances the rows are made from) is prefetched a row ahead over
// the span's input columns: the render wrote it long before (a face is larger than the caches),
// and each span row starts a new stream the hardware prefetcher has not seen, so without the
// hint the row makers wait on memory (a prefetch changes no value).
// Optional new_row_out(y, row, span, dst, window, ext): where output row y's window has a new
// bottom row (row = y + r, inside the face), makes that row's sums into dst (its ring slots, the
// window's last row of each plane) and writes output row y in one pass, returning true; false
// leaves both to hrow and out_row.
template <class T = double, class HRow, class OutRow, class NewRowOut = std::nullptr_t>
void fused_box(int w, int h, int k, int planes, const FaceTiles* tiles, const float* src,
               const HRow& hrow, const OutRow& out_row, const NewRowOut& new_row_out = nullptr) {
  constexpr bool has_new_row_out = !std::is_same_v<NewRowOut, std::nullptr_t>;
  const int r = k / 2;
  const int bands = (h + kTexelTile - 1) / kTexelTile;
  parallel_for_chunks(size_t(bands), 1, [&](size_t b0, size_t b1) {
    // One uninitialized block, 64-byte aligned, its rows (row_len values) whole lines: a
    // kernel whose steps start at x = 0 of a row (MSM's AVX-512 row, msm_hsum_out_lines) then
    // never straddles two lines with a 64-byte load or store (with rows of w = 1030 floats, 24
    // bytes past a line each, every one of them did: docs/performance.md). Every value is
    // written before it is read.
    constexpr size_t kLine = 64 / sizeof(T);
    const size_t row_len = (size_t(w) + kLine - 1) / kLine * kLine;
    const size_t ew = (size_t(w) + size_t(k) - 1 + kLine - 1) / kLine * kLine;
    const size_t n_ring = size_t(k) * size_t(planes) * row_len;
    // out_row's scratch: (planes + 1) × w doubles' worth of bytes, whatever T.
    const size_t n_out = (size_t(planes) + 1) * row_len * (sizeof(double) / sizeof(T));
    struct LineDelete {
      void operator()(T* p) const { ::operator delete(p, std::align_val_t(64)); }
    };
    const std::unique_ptr<T[], LineDelete> ring(static_cast<T*>(
        ::operator new((n_ring + size_t(planes) * ew + n_out) * sizeof(T), std::align_val_t(64))));
    T* const ext = ring.get() + n_ring;
    T* const out = ext + size_t(planes) * ew;
    auto slot = [&](int yy, int c) {
      return ring.get() + (size_t(yy % k) * size_t(planes) + size_t(c)) * row_len;
    };
    std::vector<T*> dst(static_cast<size_t>(planes));
    std::vector<const T*> window(size_t(planes) * size_t(k));
    std::vector<TexelSpan> spans;
    for (size_t band = b0; band < b1; ++band) {
      tile_spans(tiles, int(band), w, spans);
      const int y0 = int(band) * kTexelTile, y1 = std::min(h, y0 + kTexelTile);
      for (const TexelSpan& span : spans) {
        const SpanCols cols = span_cols(span, w, r);
        int next = std::max(0, y0 - r);
        for (int y = y0; y < y1; ++y) {
          const int last = std::min(h - 1, y + r);
          // The window's new bottom row, left to new_row_out.
          const int defer = has_new_row_out && last == y + r ? last : -1;
          for (; next <= last; ++next) {
            if (next + 1 < h)
              prefetch_bytes(src + size_t(next + 1) * size_t(w) + size_t(cols.in0),
                             size_t(cols.in_n) * sizeof(float));
            if (next == defer) break;
            for (int c = 0; c < planes; ++c) dst[size_t(c)] = slot(next, c);
            hrow(next, cols, dst.data(), ext);
          }
          for (int c = 0; c < planes; ++c)
            for (int j = -r; j <= r; ++j)
              window[size_t(c) * size_t(k) + size_t(j + r)] = slot(std::clamp(y + j, 0, h - 1), c);
          if constexpr (has_new_row_out) {
            if (next == defer) {
              ++next;
              for (int c = 0; c < planes; ++c) dst[size_t(c)] = slot(defer, c);
              if (new_row_out(y, defer, cols, dst.data(), window.data(), ext)) continue;
              hrow(defer, cols, dst.data(), ext);
            }
          }
          out_row(y, cols, window.data(), out);
        }
      }
    }
    stream_fence();  // out_row's stream copies (core/stream_copy.h) before the chunk ends
  });
}

// Calls f(std::integral_constant<int, K>) for the widths with compiled kernels; false otherwise.
template <class F>
bool with_fixed_width(int k, const F& f) {
  switch (k) {
    case 1: f(std::integral_constant<int, 1>{}); return true;
    case 3: f(std::integral_constant<int, 3>{}); return true;
    case 5: f(std::integral_constant<int, 5>{}); return true;
    case 7: f(std::integral_constant<int, 7>{}); return true;
    case 9: f(std::integral_constant<int, 9>{}); return true;
    default: return false;
  }
}

}  // namespace
}  // namespace shadowlab
