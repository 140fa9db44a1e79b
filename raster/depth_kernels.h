#pragma once
// Depth-only kernels for blocks 8 pixels wide: exact int64 coverage (top-left rule already
// folded into the edge values) and a depth test against the float plane
//   1/w(i, r) = clamp((z0 + z_dy · float(oy + r)) + z_dx · float(ox + i), z_lo, z_hi),
// computed with the same IEEE operations (multiply, then add; no FMA) in every variant, so the
// AVX-512 and AVX2 paths and the scalar oracle give identical bits. The variant is
// process_isa()'s table of DepthKernels, taken once per process (depth_row8,
// rasterize_depth_in_rect).
#include <cstddef>
#include <cstdint>

#include "core/isa.h"

namespace shadowlab {

// Name of the depth kernels in use (process_isa()'s table): "avx512" (whole triangles),
// "avx2" (rows of blocks) or "scalar" (the oracle); SHADOWLAB_ISA=avx2 keeps AVX2,
// SHADOWLAB_SCALAR=1 the scalar oracle.
const char* depth_kernel_name();

// A row of `blocks` blocks side by side, each `rows` rows × 8 pixels, in one call (the walk over
// a triangle's blocks in a tile row, kept in the kernel's registers): block j starts at pixel
// 8·j of the row, with edge values edge[k] + j · block_step[k] there; it is skipped when
// edge + hi_off < 0 for some edge (no pixel centre of it covered) and taken as wholly covered
// when edge + lo_off >= 0 for every edge (then its edges need no test). Row r of the block
// writes z + r · stride.
struct DepthRow8 {
  int64_t edge[3], step_x[3], step_y[3];
  int64_t block_step[3], lo_off[3], hi_off[3];
  float z0, z_dx, z_dy;  // the triangle's plane (see TriangleSetup)
  float z_lo, z_hi;
  int ox, oy;            // first block's origin minus the triangle's (min_x, min_y)
  int rows;              // 1..8
  int blocks;            // >= 0
  uint32_t id = 0;
  uint32_t* ids = nullptr;  // first block's ids, when not null
};
using DepthRow8Fn = void (*)(const DepthRow8& r, float* z, size_t stride);

// Scalar reference: every pixel of every block tested on its own (no block-level test).
void depth_row8_scalar(const DepthRow8& r, float* z, size_t stride);

// A whole triangle inside the rectangle [x0, x1) × [y0, y1) of a width-wide target (z, and
// ids when not null): rasterize_depth_in_rect's walk and depth_row8's blocks in one AVX-512
// function, the per-triangle fields in registers; the viewport's right edge cuts the last
// block's lanes (masked loads and stores) where the walk takes that block pixel by pixel.
// Per pixel the same coverage and float operations, so the same bits.
struct TriangleSetup;
using DepthTriangleFn = void (*)(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                 float* z, uint32_t* ids, size_t width);

// The family's table per instruction set (docs/simd.md). row8: the scalar oracle, or the AVX2
// row (raster/depth_kernels_avx2.cpp), which the AVX-512 table uses too; triangle: the AVX-512
// walk (depth_kernels_avx512.cpp), nullptr in the narrower tables (their callers walk the
// blocks themselves, rasterize_depth_in_rect, calling row8).
struct DepthKernels {
  Isa isa;  // the widest instruction set the table's kernels were compiled for
  DepthRow8Fn row8;
  DepthTriangleFn triangle;
};
const DepthKernels& depth_kernels(Isa isa);

// process_isa()'s row, taken at the first call.
inline void depth_row8(const DepthRow8& r, float* z, size_t stride) {
  static const DepthRow8Fn fn = depth_kernels(process_isa()).row8;
  fn(r, z, stride);
}

}  // namespace shadowlab
