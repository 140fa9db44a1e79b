#pragma once
// Depth-only kernels for an 8-pixel-wide block: exact int64 coverage (top-left rule already
// folded into the edge values) and a depth test against the float plane
//   1/w(i, r) = clamp((z0 + z_dy · float(oy + r)) + z_dx · float(ox + i), z_lo, z_hi),
// computed with the same IEEE operations (multiply, then add; no FMA) in every variant, so the
// AVX2 path and the scalar oracle give identical bits. The variant is chosen once at run time
// (AVX2 when the CPU has it, unless SHADOWLAB_SCALAR=1 forces the scalar path).
#include <cstddef>
#include <cstdint>

namespace shadowlab {

// A block of `rows` rows × 8 pixels: edge[] holds the biased edge values at the block's first
// pixel, step_x/step_y the per-pixel and per-row increments; row r writes z + r · stride.
struct DepthBlock8 {
  int64_t edge[3], step_x[3], step_y[3];
  int64_t lane_x[3][8];  // step_x[k] · i for i = 0..7 (filled once per triangle by the caller)
  float z0, z_dx, z_dy;  // the triangle's plane (see TriangleSetup)
  float z_lo, z_hi;      // clamp range of the plane value
  int ox, oy;            // block origin minus the triangle's (min_x, min_y)
  int rows;              // 1..8
  bool inside = false;   // every pixel of the block is covered: kernels may skip the edges
  uint32_t id = 0;       // triangle id written where the depth test passes...
  uint32_t* ids = nullptr;  // ...at ids + r · stride + i, when not null
};
using DepthBlock8Fn = void (*)(const DepthBlock8& b, float* z, size_t stride);

// Scalar reference: the test oracle of the fast path.
void depth_block8_scalar(const DepthBlock8& b, float* z, size_t stride);
// The AVX2 path, or nullptr when this build or CPU has none.
DepthBlock8Fn depth_block8_avx2();
// The AVX-512 path (F, VL, DQ), or nullptr when this build or CPU has none.
DepthBlock8Fn depth_block8_avx512();
// The variant in use, chosen once per process.
DepthBlock8Fn depth_block8_selected();
// Name of the variant in use: "avx512", "avx2" or "scalar" (SHADOWLAB_ISA=avx2 keeps AVX2,
// SHADOWLAB_SCALAR=1 the scalar oracle).
const char* depth_kernel_name();

inline void depth_block8(const DepthBlock8& b, float* z, size_t stride) {
  static const DepthBlock8Fn fn = depth_block8_selected();
  fn(b, z, stride);
}

// A row of `blocks` blocks side by side, each `rows` rows × 8 pixels, in one call (the walk over
// a triangle's blocks in a tile row, kept in the kernel's registers): block j starts at pixel
// 8·j of the row, with edge values edge[k] + j · block_step[k] there; it is skipped when
// edge + hi_off < 0 for some edge (no pixel centre of it covered) and taken as wholly covered
// when edge + lo_off >= 0 for every edge, as DepthBlock8::inside. Block j is depth_block8 of
// that block, bit for bit.
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

// Scalar reference: each block through depth_block8_scalar.
void depth_row8_scalar(const DepthRow8& r, float* z, size_t stride);
DepthRow8Fn depth_row8_avx2();
// The scalar oracle when depth_block8_selected() is, else the AVX2 row (the AVX-512 path walks
// whole triangles instead: depth_triangle_selected).
DepthRow8Fn depth_row8_selected();

inline void depth_row8(const DepthRow8& r, float* z, size_t stride) {
  static const DepthRow8Fn fn = depth_row8_selected();
  fn(r, z, stride);
}

// A whole triangle inside the rectangle [x0, x1) × [y0, y1) of a width-wide target (z, and
// ids when not null): rasterize_depth_in_rect's walk and depth_row8's blocks in one AVX-512
// function, the per-triangle fields in registers; the viewport's right edge cuts the last
// block's lanes (masked loads and stores) where the walk takes that block pixel by pixel.
// Per pixel the same coverage and float operations, so the same bits.
struct TriangleSetup;
using DepthTriangleFn = void (*)(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                 float* z, uint32_t* ids, size_t width);
DepthTriangleFn depth_triangle_avx512();
// The AVX-512 form when depth_block8_selected() is the AVX-512 kernel, else nullptr.
DepthTriangleFn depth_triangle_selected();

}  // namespace shadowlab
