// The scalar table of techniques/filters/moments_common/moment_rows.h (the oracle: moment_rows.inl's loops compiled for
// the baseline) and the getter.
#include "techniques/filters/moments_common/moment_rows.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/exp_log.h"
#include "techniques/filters/msm/moment_bound.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector tables (techniques/filters/moments_common/moment_rows_avx2.cpp, moment_rows_avx512.cpp).
extern const MomentRowKernels kMomentRowsAvx2;
extern const MomentRowKernels kMomentRowsAvx512;
#endif

namespace moment_rows_scalar {

#include "techniques/filters/moments_common/moment_rows.inl"

}  // namespace moment_rows_scalar

namespace {

constexpr MomentRowKernels kMomentRowsScalar = moment_rows_scalar::plain_table(Isa::scalar);

}  // namespace

const MomentRowKernels& moment_row_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kMomentRowsAvx512;
  if (isa == Isa::avx2) return kMomentRowsAvx2;
#endif
  (void)isa;
  return kMomentRowsScalar;
}

}  // namespace shadowlab
