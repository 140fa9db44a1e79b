#include "raster/depth_kernels.h"

#include <algorithm>

#include "core/isa.h"
#include "raster/setup.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector kernels (raster/depth_kernels_avx2.cpp, depth_kernels_avx512.cpp).
namespace depth_kernels_avx2 {
void row8(const DepthRow8& r, float* z, size_t stride);
}
namespace depth_kernels_avx512 {
void triangle(const TriangleSetup& s, int x0, int y0, int x1, int y1, float* z, uint32_t* ids,
              size_t width);
}
#endif

void depth_row8_scalar(const DepthRow8& r, float* z, size_t stride) {
  for (int j = 0; j < r.blocks; ++j) {
    float* const zb = z + 8 * size_t(j);
    uint32_t* const idb = r.ids ? r.ids + 8 * size_t(j) : nullptr;
    const int ox = r.ox + 8 * j;
    for (int row = 0; row < r.rows; ++row) {
      const float zy = r.z0 + r.z_dy * float(r.oy + row);
      float* const zr = zb + size_t(row) * stride;
      int64_t e[3];
      for (int k = 0; k < 3; ++k)
        e[k] = r.edge[k] + r.block_step[k] * j + r.step_y[k] * int64_t(row);
      for (int i = 0; i < 8; ++i, e[0] += r.step_x[0], e[1] += r.step_x[1], e[2] += r.step_x[2]) {
        if ((e[0] | e[1] | e[2]) < 0) continue;
        const float iw = std::min(std::max(zy + r.z_dx * float(ox + i), r.z_lo), r.z_hi);
        if (iw > zr[i]) {
          zr[i] = iw;
          if (idb) idb[size_t(row) * stride + size_t(i)] = r.id;
        }
      }
    }
  }
}

namespace {

constexpr DepthKernels kDepthScalar{Isa::scalar, depth_row8_scalar, nullptr};
#if defined(__x86_64__)
constexpr DepthKernels kDepthAvx2{Isa::avx2, depth_kernels_avx2::row8, nullptr};
constexpr DepthKernels kDepthAvx512{Isa::avx512, depth_kernels_avx2::row8,
                                    depth_kernels_avx512::triangle};
#endif

}  // namespace

const DepthKernels& depth_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kDepthAvx512;
  if (isa == Isa::avx2) return kDepthAvx2;
#endif
  (void)isa;
  return kDepthScalar;
}

const char* depth_kernel_name() { return isa_name(depth_kernels(process_isa()).isa); }

}  // namespace shadowlab
