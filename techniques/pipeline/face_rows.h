#pragma once
// The face renderer's tile epilogue (techniques/pipeline/face_render.cpp) as a kernel family
// (docs/simd.md): rasterized 1/w turned into the normalised radial distance in place, with or
// without the tile's minimum (ESM's shift). Branch-free rows, so they vectorize: an empty texel
// (1/w = 0) divides to +inf, "nothing seen"; sqrt, multiply, add and divide are exact IEEE
// operations in a fixed order, and min is exact (a NaN never compares less), so every table
// gives the scalar table's bits.
#include <cstddef>

#include "core/isa.h"

namespace shadowlab {

// A gnomonic face's row: row[x] = sqrt((1 + u²) + v²) · inv_far / row[x] for x in [x0, x1),
// u = u0 + (x + ½)·du (the texel centre's plane coordinates (u, v)).
using RadialRowFn = void (*)(float* row, int x0, int x1, float u0, float du, float v,
                             float inv_far);
// A paraboloid face's row: w is the radial distance itself, row[x] = inv_far / row[x].
using ParaboloidRowFn = void (*)(float* row, int x0, int x1, float inv_far);
// radial_row over rows [y0, y1) of a tile (row y at out + y·stride, v = top − (y + ½)·dv), and
// the smallest result (+inf when none is smaller).
using RadialTileMinFn = float (*)(float* out, size_t stride, int x0, int x1, int y0, int y1,
                                  float u0, float du, float top, float dv, float inv_far);
// paraboloid_row and the smallest result.
using ParaboloidRowMinFn = float (*)(float* row, int x0, int x1, float inv_far);

struct FaceRowKernels {
  Isa isa;  // the instruction set the rows were compiled for
  RadialRowFn radial_row;
  ParaboloidRowFn paraboloid_row;
  RadialTileMinFn radial_tile_min;
  ParaboloidRowMinFn paraboloid_row_min;
};
const FaceRowKernels& face_row_kernels(Isa isa);

// The smallest value of row[x0, x1) (+inf when none is smaller), ignoring NaN: the scalar
// minimum every table's tails use.
float face_row_min_scalar(const float* row, int x0, int x1);

}  // namespace shadowlab
