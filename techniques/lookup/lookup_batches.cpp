// The tables of techniques/lookup/lookup_batches.h: the scalar one (no kernels: the callers' scalar
// loops are the oracle) and the getter.
#include "techniques/lookup/lookup_batches.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector tables (techniques/lookup/lookup_batches_avx2.cpp, lookup_batches_avx512.cpp).
extern const LookupBatchKernels kLookupBatchesAvx2;
extern const LookupBatchKernels kLookupBatchesAvx512;
#endif

namespace {

constexpr LookupBatchKernels scalar_table() {
  LookupBatchKernels t{};
  t.isa = Isa::scalar;
  return t;
}
constexpr LookupBatchKernels kLookupBatchesScalar = scalar_table();

}  // namespace

const LookupBatchKernels& lookup_batch_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kLookupBatchesAvx512;
  if (isa == Isa::avx2) return kLookupBatchesAvx2;
#endif
  (void)isa;
  return kLookupBatchesScalar;
}

}  // namespace shadowlab
