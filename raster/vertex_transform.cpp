#include "raster/vertex_transform.h"

#include "raster/clip.h"

namespace shadowlab {

#if defined(__x86_64__)
// The AVX2 form (raster/vertex_transform_avx2.cpp).
namespace vertex_transform_avx2 {
void transform(const mat4& m, const vec3* pos, size_t n, float guard_x, float guard_y, vec4* clip,
               uint32_t* code);
}
#endif

void transform_vertices_scalar(const mat4& m, const vec3* pos, size_t n, float guard_x,
                               float guard_y, vec4* clip, uint32_t* code) {
  for (size_t i = 0; i < n; ++i) {
    clip[i] = m * vec4(pos[i], 1.0f);
    code[i] = vertex_outcode(clip[i], guard_x, guard_y);
  }
}

namespace {

constexpr VertexTransformKernels kTransformScalar{Isa::scalar, transform_vertices_scalar};
#if defined(__x86_64__)
constexpr VertexTransformKernels kTransformAvx2{Isa::avx2, vertex_transform_avx2::transform};
#endif

}  // namespace

const VertexTransformKernels& vertex_transform_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa >= Isa::avx2) return kTransformAvx2;
#endif
  (void)isa;
  return kTransformScalar;
}

}  // namespace shadowlab
