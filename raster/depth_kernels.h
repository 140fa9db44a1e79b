#pragma once
// Depth-only kernels for one 8-pixel row of a block: exact int64 coverage (top-left rule
// already folded into the edge values) and a depth max with the float plane
//   1/w(i) = zy + z_dx · float(ox + i),  i = 0..7,
// computed with the same IEEE operations (multiply, then add; no FMA) in every variant, so the
// AVX2 path and the scalar oracle give identical bits. The variant is chosen once at run time
// (AVX2 when the CPU has it, unless SHADOWLAB_SCALAR=1 forces the scalar path).
#include <cstddef>
#include <cstdint>

namespace shadowlab {

using DepthRow8Fn = void (*)(const int64_t edge[3], const int64_t step_x[3], float zy, float z_dx,
                             int ox, float* z);

// A block of `rows` rows × 8 pixels: edge[] holds the biased edge values at the block's first
// pixel, step_x/step_y the per-pixel and per-row increments; row r uses the depth plane
// zy = z_row0 + z_dy · float(oy + r) and writes z + r · stride. Same arithmetic as calling
// depth_row8 once per row.
struct DepthBlock8 {
  int64_t edge[3], step_x[3], step_y[3];
  float z0, z_dx, z_dy;  // the triangle's plane (see TriangleSetup)
  int ox, oy;            // block origin minus the triangle's (min_x, min_y)
  int rows;              // 1..8
};
using DepthBlock8Fn = void (*)(const DepthBlock8& b, float* z, size_t stride);

// Scalar reference: the test oracle of the fast path.
void depth_row8_scalar(const int64_t edge[3], const int64_t step_x[3], float zy, float z_dx,
                       int ox, float* z);
void depth_block8_scalar(const DepthBlock8& b, float* z, size_t stride);
// The AVX2 path, or nullptr when this build or CPU has none.
DepthRow8Fn depth_row8_avx2();
DepthBlock8Fn depth_block8_avx2();
DepthBlock8Fn depth_block8_selected();
// The variant in use (chosen once).
DepthRow8Fn depth_row8_selected();
// Name of the variant in use: "avx2" or "scalar".
const char* depth_kernel_name();

inline void depth_row8(const int64_t edge[3], const int64_t step_x[3], float zy, float z_dx,
                       int ox, float* z) {
  static const DepthRow8Fn fn = depth_row8_selected();
  fn(edge, step_x, zy, z_dx, ox, z);
}

inline void depth_block8(const DepthBlock8& b, float* z, size_t stride) {
  static const DepthBlock8Fn fn = depth_block8_selected();
  fn(b, z, stride);
}

}  // namespace shadowlab
