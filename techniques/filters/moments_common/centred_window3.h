#pragma once
// The 3 × 3 box filter of VSM's and EVSM's two moments (k = 3, the default blur) as one 9-tap
// window per texel in float, centred on the texel's own value: with c the centre value and
// δ_i = v_i − c over the window (rows top to bottom, columns left to right),
//   mean = c + Σδ_i/9,   variance = Σ(δ_i/3)² − (Σδ_i/9)²   (+0 where that is not > 0).
// The centre's δ is 0, so (Σδ_i)² ≤ 8·Σδ_i² (Cauchy–Schwarz on the other 8): the subtraction
// keeps at least 1/9 of Σ(δ_i/3)², and the variance carries at most 9 times the sums' relative
// rounding, where the uncentred E[v²] − E[v]² of float sums loses everything once the variance
// is below ~1e-7 of E[v²] (hence the separable filters' double sums for the other widths:
// techniques/filters/moments_common/moment_filter.h). Squaring δ/3 rather than δ keeps the sum of 8 squares finite for
// EVSM's largest exponent: |δ| < e^c, and 8·e^(2c)/9 < FLT_MAX for c ≤ 44.36. The bounds and
// their measurement: docs/techniques/vsm.md, Precision.
#include "core/isa.h"

namespace shadowlab {

// row: output texels x = 0 .. n − 1 of one row from the three extended input rows of its windows
// (n + 2 values each: texel x's window is r0, r1, r2 [x .. x + 2], its centre r1[x + 1]):
// texel x's mean at mean[stride·x] and variance at var[stride·x]. The vector kernels store
// stride 2 with var = mean + 1 (the interleaved map) straight from registers; other layouts
// through a small buffer.
using CentredWindow3RowFn = void (*)(const float* r0, const float* r1, const float* r2, int n,
                                    float* mean, float* var, int stride);

// The family's table per instruction set (docs/simd.md): the scalar row is the oracle; the AVX2
// and AVX-512 rows (one body, techniques/filters/moments_common/centred_window3_simd.inl) give its bits, the same float
// operations in the same order (-ffp-contract=off), which tests/techniques/centred_window3_test.cpp
// checks for every instruction set the CPU runs.
struct CentredWindow3Kernels {
  Isa isa;  // the instruction set the row was compiled for
  CentredWindow3RowFn row;
};
const CentredWindow3Kernels& centred_window3_kernels(Isa isa);

}  // namespace shadowlab
