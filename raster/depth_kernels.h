#pragma once
// Depth-only kernels for blocks 8 pixels wide: exact int64 coverage (top-left rule already
// folded into the edge values) and a depth test against the float plane
//   1/w(i, r) = clamp((z0 + z_dy · float(oy + r)) + z_dx · float(ox + i), z_lo, z_hi),
// computed with the same IEEE operations (multiply, then add; no FMA) in every variant, so the
// AVX-512 and AVX2 paths and the scalar oracle give identical bits. The variant is chosen once
// at run time (depth_kernel_name).
#include <cstddef>
#include <cstdint>

namespace shadowlab {

// Name of the depth kernels in use, chosen once per process: "avx512" or "avx2" (whole
// triangles, depth_triangle_selected) or "scalar" (the oracle, rows of blocks);
// SHADOWLAB_ISA=avx2 keeps AVX2, SHADOWLAB_SCALAR=1 the scalar oracle.
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

// Scalar reference: every pixel of every block tested on its own (no block-level test). The
// rasterizer's depth-only path when the scalar oracle is in use; the AVX2 and AVX-512 paths walk
// whole triangles instead (depth_triangle_selected).
void depth_row8_scalar(const DepthRow8& r, float* z, size_t stride);

inline void depth_row8(const DepthRow8& r, float* z, size_t stride) {
  depth_row8_scalar(r, z, stride);
}

// A whole triangle inside the rectangle [x0, x1) × [y0, y1) of a width-wide target (z, and
// ids when not null): rasterize_depth_in_rect's walk and depth_row8's blocks in one SIMD
// function, the per-triangle fields in registers. The block cut by the viewport's right edge:
// masked loads and stores in AVX-512, pixel by pixel in AVX2. Per pixel the same coverage and
// float operations as the scalar oracle, so the same bits.
struct TriangleSetup;
using DepthTriangleFn = void (*)(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                 float* z, uint32_t* ids, size_t width);
DepthTriangleFn depth_triangle_avx512();
// The AVX2 form (nullptr without AVX2): 8 int32 lanes per edge in the blocks whose values fit,
// the int64 halves (block_rows_avx2) in the others, the cut block pixel by pixel.
DepthTriangleFn depth_triangle_avx2();
// The form of the kernels in use (depth_kernel_name): AVX-512 or AVX2; nullptr for the scalar
// oracle, which walks rows of blocks (depth_row8_scalar).
DepthTriangleFn depth_triangle_selected();

}  // namespace shadowlab
