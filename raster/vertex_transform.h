#pragma once
// The front end's first step (tile_binner.cpp): world-space vertices to clip space through one
// matrix, with each vertex's outcode (raster/clip.h), once per vertex rather than once per
// triangle corner. The AVX2 form does 8 vertices at a time with the scalar form's operations in
// the same order, so both give the same bits (tests/raster/vertex_transform_test.cpp).
#include <cstddef>
#include <cstdint>

#include "core/isa.h"
#include "core/math.h"

namespace shadowlab {

// clip[i] = m · (pos[i], 1) in glm's order ((m0·x + m1·y) + (m2·z + m3)), and
// code[i] = vertex_outcode(clip[i], guard_x, guard_y), for i in [0, n).
using TransformVerticesFn = void (*)(const mat4& m, const vec3* pos, size_t n, float guard_x,
                                     float guard_y, vec4* clip, uint32_t* code);

// The scalar form: the oracle, and the vector forms' tail.
void transform_vertices_scalar(const mat4& m, const vec3* pos, size_t n, float guard_x,
                               float guard_y, vec4* clip, uint32_t* code);

// The family's table per instruction set (docs/simd.md): the scalar form, or the AVX2 form
// (raster/vertex_transform_avx2.cpp), which AVX-512 uses too (the gathers and the 4 × 8
// transpose bound it, not the width).
struct VertexTransformKernels {
  Isa isa;  // the instruction set the transform was compiled for
  TransformVerticesFn transform;
};
const VertexTransformKernels& vertex_transform_kernels(Isa isa);

}  // namespace shadowlab
