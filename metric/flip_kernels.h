#pragma once
// FLIP's vector kernels (metric/flip.cpp) per instruction set (docs/simd.md): the filter rows
// (written once, metric/flip_rows.inl, vectorized per file) and power() of many values. Every
// table gives the scalar table's bits: the rows are element-wise IEEE multiplies and adds in a
// fixed order (no FMA under -ffp-contract=off); the vector power performs exp_d's and log_d's
// operations lane by lane (core/exp_log_avx2.h, exp_log_avx512.h).
#include <cstddef>

#include "core/isa.h"

namespace shadowlab {

struct FlipKernels {
  Isa isa;  // the instruction set the kernels were compiled for
  // dst[x] += k·src[x] for x < n.
  void (*axpy)(double k, const double* src, int n, double* dst);
  // out[x] = Σ_j k[j]·rows[j][x] for x < n, each sum from 0 in j order.
  void (*weighted_rows)(const double* const* rows, const double* k, int taps, int n, double* out);
  // out[i] = x[i]^(p ? p[i] : p0) for the first values, whole vectors of them (x >= 0; 0 where
  // x < 2^-1000, 1 where the exponent is 0: flip.cpp's power()); returns how many it wrote,
  // the caller takes the rest. nullptr in the scalar table (the caller's power() loop).
  size_t (*power)(const double* x, const double* p, double p0, size_t n, double* out);
};
const FlipKernels& flip_kernels(Isa isa);

}  // namespace shadowlab
