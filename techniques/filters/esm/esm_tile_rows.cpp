// The scalar table of techniques/filters/esm/esm_tile_rows.h (the oracle) and the getter.
#include "techniques/filters/esm/esm_tile_rows.h"

#include <algorithm>

#include "core/exp_log.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector tables (techniques/filters/esm/esm_tile_rows_avx2.cpp, esm_tile_rows_avx512.cpp).
extern const EsmTileKernels kEsmTilesAvx2;
extern const EsmTileKernels kEsmTilesAvx512;
#endif

namespace esm_tile_rows_scalar {

void stage_row(const float* src, int n, int lead, int pad_to, float* dst) {
  for (int x = 0; x < n; ++x) dst[lead + x] = src[x] < 1.0f ? src[x] : 1.0f;
  for (int x = 0; x < lead; ++x) dst[x] = dst[lead];
  for (int x = lead + n; x < pad_to; ++x) dst[x] = dst[lead + n - 1];
}

void exp_rows(const float* src, size_t pitch, int rows, int n, double c, double s, bool,
              float* dst) {
  for (int yy = 0; yy < rows; ++yy)
    for (int x = 0; x < n; ++x)
      dst[size_t(yy) * kEsmTilePitch + size_t(x)] =
          exp_f(float(c * (double(src[size_t(yy) * pitch + size_t(x)]) - s)));
}

void range(const float* src, size_t pitch, int rows, int n, float& lo, float& hi) {
  for (int yy = 0; yy < rows; ++yy)
    for (int x = 0; x < n; ++x) {
      lo = std::min(lo, src[size_t(yy) * pitch + size_t(x)]);
      hi = std::max(hi, src[size_t(yy) * pitch + size_t(x)]);
    }
}

}  // namespace esm_tile_rows_scalar

namespace {

constexpr EsmTileKernels kEsmTilesScalar{Isa::scalar, esm_tile_rows_scalar::stage_row,
                                         esm_tile_rows_scalar::exp_rows,
                                         esm_tile_rows_scalar::range, nullptr};

}  // namespace

const EsmTileKernels& esm_tile_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kEsmTilesAvx512;
  if (isa == Isa::avx2) return kEsmTilesAvx2;
#endif
  (void)isa;
  return kEsmTilesScalar;
}

}  // namespace shadowlab
