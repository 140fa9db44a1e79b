#include "metric/flip_kernels.h"

#include <cstring>

namespace shadowlab {

#if defined(__x86_64__)
// The vector tables' kernels (metric/flip_avx2.cpp, flip_avx512.cpp).
namespace flip_avx2 {
void axpy(double k, const double* src, int n, double* dst);
void weighted_rows(const double* const* rows, const double* k, int taps, int n, double* out);
size_t power(const double* x, const double* p, double p0, size_t n, double* out);
}  // namespace flip_avx2
namespace flip_avx512 {
void axpy(double k, const double* src, int n, double* dst);
void weighted_rows(const double* const* rows, const double* k, int taps, int n, double* out);
size_t power(const double* x, const double* p, double p0, size_t n, double* out);
}  // namespace flip_avx512
#endif

// The scalar rows: the oracle (baseline code).
namespace flip_scalar {
#include "metric/flip_rows.inl"
}  // namespace flip_scalar

namespace {

constexpr FlipKernels kFlipScalar{Isa::scalar, flip_scalar::axpy, flip_scalar::weighted_rows,
                                  nullptr};
#if defined(__x86_64__)
constexpr FlipKernels kFlipAvx2{Isa::avx2, flip_avx2::axpy, flip_avx2::weighted_rows,
                                flip_avx2::power};
constexpr FlipKernels kFlipAvx512{Isa::avx512, flip_avx512::axpy, flip_avx512::weighted_rows,
                                  flip_avx512::power};
#endif

}  // namespace

const FlipKernels& flip_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kFlipAvx512;
  if (isa == Isa::avx2) return kFlipAvx2;
#endif
  (void)isa;
  return kFlipScalar;
}

}  // namespace shadowlab
