#pragma once
// The row kernels of the moment filters (techniques/filters/moments_common/moment_filter.h) as one kernel family
// (docs/simd.md): VSM's and EVSM's two moments (moment_filter.cpp), MSM's four power moments and
// their 16-bit store (moment_filter_msm.cpp, moment_shadow_map.cpp), ESM's exponentials and logs
// (moment_filter_esm.cpp). The fused box driver that calls them is techniques/moment_box.h.
//
// Two kinds of kernel:
// - plain loops (techniques/filters/moments_common/moment_rows.inl), written once and compiled by each table's file for
//   its set, so that the compiler vectorizes them for AVX2 or AVX-512 (every table has them);
// - hand-written rows with intrinsics, one form per set (moment_rows_avx2.cpp,
//   moment_rows_avx512.cpp): the exp, log and warp rows, and the fused output rows that write
//   the interleaved maps straight from registers. The scalar table's fused rows are nullptr:
//   its callers compose them from the plain rows (the same operations in the same order).
// Element-wise IEEE arithmetic in a fixed order (-ffp-contract=off) gives every table the scalar
// table's bits (tests/techniques/moment_rows_test.cpp, MomentFilter.*BitForBit).
//
// The fixed-width kernels take the box width K as a compile-time constant (their k-term sums
// stay in registers); a table holds one per compiled width, at kMomentWidthSlot(K).
#include <cstddef>

#include "core/isa.h"

namespace shadowlab {

// The box widths with compiled fixed-width kernels: 1, 3, 5, 7, 9, at slots 0 .. 4.
inline constexpr int kMomentWidths = 5;
constexpr int moment_width_slot(int k) { return k / 2; }

// --- runtime-width rows (the fixed-width kernels' oracle) -------------------------------------
// out[x] = Σ_{i<k} ext[x + i], added in i order from 0 (ext: the row extended by k/2 clamped
// texels on each side).
using HsumRowDFn = void (*)(const double* ext, int w, int k, double* out);
using HsumRowFFn = void (*)(const float* ext, int w, int k, float* out);
// dst[x] = (rows[0][x] + … + rows[k − 1][x]) × inv, added in row order.
using VsumRowsDFn = void (*)(const double* const* rows, int w, int k, double inv, double* dst);
using VsumRowsFFn = void (*)(const float* const* rows, int w, int k, float inv, float* dst);

// --- per-texel rows ---------------------------------------------------------------------------
// out[x] = min(row[x], 1) as finite_dist (NaN and +inf → 1).
using FiniteRowFn = void (*)(const float* row, int n, float* out);
// VSM: m1 = d, m2 = d² in double (d = finite_dist(row[x])).
using MomentRowFn = void (*)(const float* row, int w, double* m1, double* m2);
// mean = float(m1), var = float(m2 − m1², +0 where that is not > 0).
using MeanVarianceRowFn = void (*)(const double* m1, const double* m2, int w, float* mean,
                                   float* var);
// EVSM: v = sign·exp_f(float(sign·c)·((d + d) − 1)) in double, m1 = v, m2 = v².
using WarpedRowFn = void (*)(const float* row, int w, double c, double sign, double* m1,
                             double* m2);
// EVSM's warp as floats: v[x] = float(sign)·exp_f(float(sign·c)·((d + d) − 1)).
using WarpRowFFn = void (*)(const float* row, int w, double c, double sign, float* v);
// out[2x] = a[x], out[2x + 1] = b[x].
using InterleaveRowFn = void (*)(const float* a, const float* b, int w, float* out);
// MSM: p[c·stride + x] = d, d², d³ = d²·d, d⁴ = d²·d² for c = 0 .. 3.
using PowerRowFn = void (*)(const float* row, int w, size_t stride, float* p);
// out[4x + c] = rows[c·w + x].
using Interleave4RowFn = void (*)(const float* rows, int w, float* out);
// MSM's 16-bit store of texels [0, n) of interleaved moments, in place (msm_encode16, clamped to
// [0, 1], rounded to a multiple of 1/65535, ties up).
using Quantize16Fn = void (*)(size_t n, float* mv);
// ESM: out[x] = exp_wide(float(c·(finite_dist(row[x]) − d_min))).
using EsmExpRowFn = void (*)(const float* row, int w, double c, double d_min, double* out);
// ESM: out[x] = float(c·d_min + log_wide(filtered[x])).
using EsmLogRowFn = void (*)(const double* filtered, int w, double c, double d_min, float* out);
// min(1, min_x finite_dist(row[x])).
using RowMinDistFn = float (*)(const float* row, int w);

// --- fixed-width rows (one per compiled width K) ------------------------------------------------
// h[x] = Σ_{i<K} ext[x + i] (double).
using HsumKFn = void (*)(const double* ext, int w, double* h);
// VSM: h1[x] = Σ d, h2[x] = Σ d² over ext[x .. x + K − 1], d widened to double.
using HsumMomentsKFn = void (*)(const float* ext, int w, double* h1, double* h2);
// VSM: the K rows of both planes (rows[0 .. K − 1], rows[K .. 2K − 1]) summed, × inv, as mean
// and variance floats.
using VsmOutKFn = void (*)(const double* const* rows, int w, double inv, float* mean,
                           float* var);
// The same straight into an interleaved (mean, variance) row.
using VsmOutInterleavedFn = void (*)(const double* const* rows, int w, double inv, float* out);
// MSM: h_c[x] = Σ_{i<K} d^(c+1) over ext[x + i], the powers as PowerRowFn forms them.
using HsumPowersKFn = void (*)(const float* ext, int w, float* h0, float* h1, float* h2,
                               float* h3);
// MSM: one plane's K rows summed in float, × inv.
using MeanOutKFn = void (*)(const float* const* rows, int w, float inv, float* out);
// MSM's four planes' means (rows[c·K .. c·K + K − 1]) straight into the interleaved map, with
// non-temporal stores (the caller fences).
using MsmOutInterleavedFn = void (*)(const float* const* rows, int w, float inv, float* out);
// HsumPowersKFn for the window's new bottom row (into h[0 .. 3], which are rows[c·K + K − 1])
// and MsmOutInterleavedFn of the output row above, in one pass.
using MsmHsumOutFn = void (*)(const float* ext, float* const* h, const float* const* rows,
                              int w, float inv, float* out);
// ESM: the K rows summed, × inv, then float(c·d_min + log_wide(·)).
using EsmOutKFn = void (*)(const double* const* rows, int w, double inv, double c, double d_min,
                           float* out);

struct MomentRowKernels {
  Isa isa;  // the instruction set the rows were compiled for
  HsumRowDFn hsum_row_d;
  HsumRowFFn hsum_row_f;
  VsumRowsDFn vsum_rows_d;
  VsumRowsFFn vsum_rows_f;
  FiniteRowFn finite_row;
  MomentRowFn moment_row;
  MeanVarianceRowFn mean_variance_row;
  WarpedRowFn warped_row;
  WarpRowFFn warp_row_f;
  InterleaveRowFn interleave_row;
  PowerRowFn power_row;
  Interleave4RowFn interleave4_row;
  Quantize16Fn quantize16;
  EsmExpRowFn esm_exp_row;
  EsmLogRowFn esm_log_row;
  RowMinDistFn row_min_dist;
  HsumKFn hsum_k[kMomentWidths];
  HsumMomentsKFn hsum_moments_k[kMomentWidths];
  VsmOutKFn vsm_out_k[kMomentWidths];
  HsumPowersKFn hsum_powers_k[kMomentWidths];
  MeanOutKFn mean_out_k[kMomentWidths];
  EsmOutKFn esm_out_k[kMomentWidths];
  // nullptr in the scalar table (its callers compose vsm_out_k and interleave_row, mean_out_k,
  // interleave4_row and a stream copy).
  VsmOutInterleavedFn vsm_out_interleaved[kMomentWidths];
  MsmOutInterleavedFn msm_out_interleaved[kMomentWidths];
  MsmHsumOutFn msm_hsum_out[kMomentWidths];
};
const MomentRowKernels& moment_row_kernels(Isa isa);

}  // namespace shadowlab
