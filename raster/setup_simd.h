#pragma once
// Triangle setup for 8 triangles at once (AVX-512 with double and int64 lanes, or AVX2 with
// double lanes): setup_triangle's
// operations for triangles that need no clipping (ClipClass::Inside: their vertices are the
// original ones, barycentrics the unit vectors), lane by lane in the same order, so each
// surviving triangle's TriangleSetup has the scalar setup's bits (tests/raster/
// setup_simd_test.cpp compares every field). The front end (tile_binner.cpp) batches its
// Inside triangles through it in submission order; clipped ones keep the scalar setup.
#include <cstdint>

#include "core/isa.h"
#include "raster/setup.h"

namespace shadowlab {

// Up to 8 triangles' clip-space vertices (x, y, w of vertex v of lane k at x[v][k] ...) and
// submission indices; lanes from `count` on are ignored.
struct SetupBatch8 {
  alignas(64) float x[3][8] = {}, y[3][8] = {}, w[3][8] = {};
  uint32_t triangle[8] = {};
  int count = 0;
};

// Sets up the batch's triangles: out[0 .. n) receives the surviving ones in lane order, and
// stats counts the others as setup_triangle does (dropped_degenerate, culled_facing). Returns n.
using SetupBatch8Fn = int (*)(const SetupBatch8& b, int width, int height, CullMode cull,
                              TriangleSetup* out, RasterStats& stats);

// The family's table per instruction set (docs/simd.md): the AVX2 form (double lanes, see
// raster/setup_simd_avx2.cpp) and the AVX-512 form (int64 and double lanes,
// setup_simd_avx512.cpp). The scalar table has none (nullptr): the front end then sets up each
// triangle itself; setup_batch8_scalar below is the oracle the tests compare the forms with.
struct SetupKernels {
  Isa isa;  // the instruction set the batch form was compiled for
  SetupBatch8Fn batch8;
};
const SetupKernels& setup_kernels(Isa isa);

// The same through setup_triangle, lane by lane: the oracle.
int setup_batch8_scalar(const SetupBatch8& b, int width, int height, CullMode cull,
                        TriangleSetup* out, RasterStats& stats);

}  // namespace shadowlab
