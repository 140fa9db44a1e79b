#pragma once
// The front end's first step (tile_binner.cpp): world-space vertices to clip space through one
// matrix, with each vertex's outcode (raster/clip.h), once per vertex rather than once per
// triangle corner. The AVX2 form does 8 vertices at a time with the scalar form's operations in
// the same order, so both give the same bits (tests/raster/vertex_transform_test.cpp).
#include <cstddef>
#include <cstdint>

#include "core/math.h"

namespace shadowlab {

// clip[i] = m · (pos[i], 1) in glm's order ((m0·x + m1·y) + (m2·z + m3)), and
// code[i] = vertex_outcode(clip[i], guard_x, guard_y), for i in [0, n).
using TransformVerticesFn = void (*)(const mat4& m, const vec3* pos, size_t n, float guard_x,
                                     float guard_y, vec4* clip, uint32_t* code);

// The scalar form: the oracle, and the path without AVX2.
void transform_vertices_scalar(const mat4& m, const vec3* pos, size_t n, float guard_x,
                               float guard_y, vec4* clip, uint32_t* code);

// The AVX2 form where process_isa() >= Isa::avx2 holds, else the scalar one.
TransformVerticesFn transform_vertices_selected();

// The AVX2 form whenever the CPU runs it (nullptr otherwise), whatever is forced: for the tests.
TransformVerticesFn transform_vertices_avx2_form();

}  // namespace shadowlab
