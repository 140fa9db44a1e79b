#pragma once
// The shared machinery of the moment filters (techniques/filters/moments_common/moment_filter.h), included only by
// their files: moment_filter.cpp (VSM's and EVSM's mean and variance), moment_filter_msm.cpp
// (MSM's four power moments and their line writers) and moment_filter_esm.cpp (ESM's log-space
// box). Here: the finite-distance helpers, the runtime-width row sums (the fixed-width kernels'
// oracle), the choice of exp and log kernels, the span columns, the fused separable box driver
// and the compiled widths.
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
#include "core/exp_log.h"
#include "core/parallel.h"
#include "core/simd_target.h"
#include "core/stream_copy.h"
#include "techniques/filters/moments_common/centred_window3.h"
#include "techniques/filters/esm/esm_float_tiles.h"
#include "techniques/pipeline/texel_tiles.h"

namespace shadowlab {
namespace {

// The row kernels are compiled for AVX-512, AVX2 and baseline x86-64, picked at load time
// (SL_ROW_CLONES is this header's, for the three moment filter files);
// element-wise IEEE arithmetic (no FMA: -ffp-contract=off) gives the same bits in every clone.
// clang 14 (the sanitizer and fuzz builds of CI) has no target_clones on templates: there the
// kernels are baseline only, which gives the same bits.
#if defined(__clang__)
#define SL_ROW_CLONES
#else
#define SL_ROW_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#endif

// Distance with "nothing seen" as the light's range: d < 1 ? d : 1.
inline float finite_dist(float d) { return d < 1.0f ? d : 1.0f; }

// finite_dist and v > 0 ? v : +0 as bit masks: the same values, but GCC if-converts (and so
// vectorizes) a ?: on doubles or floats only when AVX is on for the whole file, not in the
// target_clones kernels below; a compare turned into an integer mask is no control flow.
inline float finite_dist_bits(float d) {
  const uint32_t keep = uint32_t(0) - uint32_t(d < 1.0f);
  return std::bit_cast<float>((std::bit_cast<uint32_t>(d) & keep) |
                              (std::bit_cast<uint32_t>(1.0f) & ~keep));
}
inline double positive_part(double v) {
  const uint64_t keep = uint64_t(0) - uint64_t(v > 0.0);
  return std::bit_cast<double>(std::bit_cast<uint64_t>(v) & keep);
}

// Smaller-magnitude one-sided difference of a row/column sample (neighbours clamped).
inline double min_diff(double prev, double here, double next) {
  const double a = here - prev, b = next - here;
  return std::fabs(a) <= std::fabs(b) ? a : b;
}

// The row loops of the fused separable box (fused_box below; filter_moments_double,
// filter_esm_log and filter_warped_moments): each input row's k-wide horizontal sums, then each
// output row's sum of its k rows. Every output is the same sequence of double additions as
// box_mean's two passes (left to right, then top to bottom, then × 1/k²); the loops run over x,
// which the compiler vectorizes without reordering any one texel's additions.

// out[x] = Σ_{i=0}^{k-1} ext[x + i], added in i order (ext: the row extended by k/2 clamped
// texels on each side).
template <class T>
SL_ROW_CLONES void hsum_row(const T* ext, int w, int k, T* out) {
  for (int x = 0; x < w; ++x) out[x] = T(0);
  for (int i = 0; i < k; ++i)
    for (int x = 0; x < w; ++x) out[x] += ext[x + i];
}

// dst[x] = (rows[0][x] + rows[1][x] + … + rows[k-1][x]) × inv, added in row order.
template <class T>
SL_ROW_CLONES void vsum_rows(const T* const* rows, int w, int k, T inv, T* dst) {
  for (int x = 0; x < w; ++x) dst[x] = rows[0][x];
  for (int j = 1; j < k; ++j)
    for (int x = 0; x < w; ++x) dst[x] += rows[j][x];
  for (int x = 0; x < w; ++x) dst[x] *= inv;
}

// The exp and log kernels a filter's rows use, chosen once per filter (core/isa.h; a
// getenv per row would cost more than some rows): ESM's exp_wide16 and log_wide16 (AVX-512),
// exp_wide8 and log_wide8 (AVX2) or the scalar exp_wide and log_wide, EVSM's exp_f16, exp_f8 or
// exp_f, each set giving the same bits (core/exp_log.h). The
// oracles (fixed_kernels false) take the scalar ones, so the tests' comparisons of the two also
// compare the kernels bit for bit.
inline Isa exp_path(bool fast) { return fast ? process_isa() : Isa::scalar; }

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

// Kernels for the common box widths with k a compile-time constant, so each x iteration keeps
// its k-term sums in registers instead of re-reading and re-storing whole rows (the runtime-k
// loops above, kept for other widths and the slope term). The additions are the same, in the
// same order: a sum starts from 0.0 (as the runtime-k hsum_row does) and adds left to right,
// rows top to bottom, then × 1/k²; so either path gives the other's bits.

// Texels to write one by one before out + S·x starts a 64-byte line (S floats per texel), so the
// vector stores after them do not straddle cache lines: large vectors' storage is 16-byte
// aligned here (glibc's mmap chunks), and a 64-byte store across two lines costs about two.
// A row whose texels never start a line returns `unreachable`: 0 for ordinary stores (they may
// straddle), w where the stores need aligned addresses (then every texel goes one by one).
inline int texels_to_line(const float* out, int floats_per_texel, int w, int unreachable = 0) {
  const uintptr_t bytes = (64 - (reinterpret_cast<uintptr_t>(out) & 63)) & 63;
  const uintptr_t texel_bytes = uintptr_t(floats_per_texel) * 4;
  if (bytes % texel_bytes != 0) return unreachable;
  return std::min(w, int(bytes / texel_bytes));
}

// ESM: h[x] = Σ_i ext[x + i] (ext: the row's exponentials, extended).
template <int K>
SL_ROW_CLONES void hsum_k(const double* ext, int w, double* h) {
  for (int x = 0; x < w; ++x) {
    double s = 0.0;
    for (int i = 0; i < K; ++i) s += ext[x + i];
    h[x] = s;
  }
}

// The finite values of a row's n texels: out[x] = finite_dist(row[x]) (VSM's kernels' input).
[[maybe_unused]] SL_ROW_CLONES void finite_row(const float* row, int n, float* out) {
  for (int x = 0; x < n; ++x) out[x] = finite_dist_bits(row[x]);
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
