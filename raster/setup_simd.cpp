#include "raster/setup_simd.h"

#include <cstring>

#include "raster/setup_simd_lanes.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector forms (raster/setup_simd_avx2.cpp, setup_simd_avx512.cpp).
namespace setup_simd_avx2 {
int batch8(const SetupBatch8& b, int width, int height, CullMode cull, TriangleSetup* out,
           RasterStats& stats);
}
namespace setup_simd_avx512 {
int batch8(const SetupBatch8& b, int width, int height, CullMode cull, TriangleSetup* out,
           RasterStats& stats);
}
#endif

int setup_batch8_scalar(const SetupBatch8& b, int width, int height, CullMode cull,
                        TriangleSetup* out, RasterStats& stats) {
  int n = 0;
  for (int k = 0; k < b.count; ++k) {
    ClipVertex v[3];
    for (int i = 0; i < 3; ++i) {
      v[i].clip = vec4(b.x[i][k], b.y[i][k], 0.0f, b.w[i][k]);
      v[i].bary = vec3(i == 0 ? 1.0f : 0.0f, i == 1 ? 1.0f : 0.0f, i == 2 ? 1.0f : 0.0f);
    }
    if (setup_triangle(v[0], v[1], v[2], b.triangle[k], width, height, cull, out[n], stats)) ++n;
  }
  return n;
}

namespace {

// The records of the lanes in `live` (bit k: lane k), in lane order: vertices 1 and 2 swapped
// where `neg`, edge e's bias 0 where top_left[e] has the lane, else −1. The conversions are
// exact for the integers; for the plane, float(double) is the scalar setup's own rounding.
template <class Int, class Real>
int write_setups_of(const SetupLanes<Int, Real>& L, int live, int neg, const int* top_left,
                    const uint32_t* triangle, TriangleSetup* out) {
  int n = 0;
  for (int k = 0; k < 8; ++k) {
    if (!((live >> k) & 1)) continue;
    TriangleSetup& s = out[n++];
    const bool swapped = (neg >> k) & 1;
    const int order[3] = {0, swapped ? 2 : 1, swapped ? 1 : 2};
    for (int e = 0; e < 3; ++e) {
      s.a[e] = int64_t(L.a[e][k]);
      s.b[e] = int64_t(L.b[e][k]);
      s.c[e] = int64_t(L.c[e][k]);
      s.bias[e] = int8_t(((top_left[e] >> k) & 1) ? 0 : -1);
      s.inv_w[e] = float(L.iw[e][k]);
      // The original vertex's unit barycentrics times its 1/w, as vec3 * float.
      const vec3 unit(order[e] == 0 ? 1.0f : 0.0f, order[e] == 1 ? 1.0f : 0.0f,
                      order[e] == 2 ? 1.0f : 0.0f);
      s.bary_over_w[e] = unit * s.inv_w[e];
    }
    s.area2 = int64_t(L.area[k]);
    s.min_x = int(L.x0[k]);
    s.max_x = int(L.x1[k]);
    s.min_y = int(L.y0[k]);
    s.max_y = int(L.y1[k]);
    s.z0 = float(L.z0[k]);
    s.z_dx = float(L.zx[k]);
    s.z_dy = float(L.zy[k]);
    s.z_lo = float(L.lo[k]);
    s.z_hi = float(L.hi[k]);
    s.triangle = triangle[k];
  }
  return n;
}

constexpr SetupKernels kSetupScalar{Isa::scalar, nullptr};
#if defined(__x86_64__)
constexpr SetupKernels kSetupAvx2{Isa::avx2, setup_simd_avx2::batch8};
constexpr SetupKernels kSetupAvx512{Isa::avx512, setup_simd_avx512::batch8};
#endif

}  // namespace

int write_setups(const SetupLanes<int64_t, float>& L, int live, int neg, const int* top_left,
                 const uint32_t* triangle, TriangleSetup* out) {
  return write_setups_of(L, live, neg, top_left, triangle, out);
}
int write_setups(const SetupLanes<double, double>& L, int live, int neg, const int* top_left,
                 const uint32_t* triangle, TriangleSetup* out) {
  return write_setups_of(L, live, neg, top_left, triangle, out);
}

const SetupKernels& setup_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kSetupAvx512;
  if (isa == Isa::avx2) return kSetupAvx2;
#endif
  (void)isa;
  return kSetupScalar;
}

}  // namespace shadowlab
