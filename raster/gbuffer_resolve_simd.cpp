#include "raster/gbuffer_resolve_simd.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector paths (raster/gbuffer_resolve_simd_avx2.cpp, gbuffer_resolve_simd_avx512.cpp).
namespace gbuffer_resolve_avx2 {
void run8(const ResolveRun8& r, int x, int y, const float* inv_w, vec3* position,
          vec3* geo_normal, float* depth_out);
void lanes8(const ResolveRun8& camera, const ResolveLanes8& lanes, int x, int y,
            const float* inv_w, vec3* position, vec3* geo_normal, float* depth_out);
}  // namespace gbuffer_resolve_avx2
namespace gbuffer_resolve_avx512 {
void lanes16(const ResolveRun8& r, const ResolveLanes16& t, int x, int y, const float* inv_w,
             vec3* position, vec3* geo_normal, float* depth_out, uint32_t* mesh_id,
             uint32_t* prim_id, uint8_t* covered);
uint32_t lanes16_runs(const uint32_t* ids, uint32_t* covered);
void lanes16_fill(ResolveLanes16& l, uint32_t mask, const vec3& e1, const vec3& e2,
                  const vec3& gn, float e2q, uint32_t mesh, uint32_t prim);
}  // namespace gbuffer_resolve_avx512
#endif

namespace {

constexpr GBufferResolveKernels kResolveScalar{Isa::scalar, nullptr, nullptr, nullptr, nullptr,
                                               nullptr};
#if defined(__x86_64__)
constexpr GBufferResolveKernels kResolveAvx2{Isa::avx2, gbuffer_resolve_avx2::run8,
                                             gbuffer_resolve_avx2::lanes8, nullptr, nullptr,
                                             nullptr};
constexpr GBufferResolveKernels kResolveAvx512{
    Isa::avx512,
    gbuffer_resolve_avx2::run8,
    gbuffer_resolve_avx2::lanes8,
    gbuffer_resolve_avx512::lanes16,
    gbuffer_resolve_avx512::lanes16_runs,
    gbuffer_resolve_avx512::lanes16_fill};
#endif

}  // namespace

const GBufferResolveKernels& gbuffer_resolve_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kResolveAvx512;
  if (isa == Isa::avx2) return kResolveAvx2;
#endif
  (void)isa;
  return kResolveScalar;
}

}  // namespace shadowlab
