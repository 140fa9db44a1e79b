#pragma once
// The lanes of raster/setup_simd.h's vector forms between their registers and the records: the
// integers as int64 (AVX-512) or as the doubles that hold them exactly (AVX2), the plane as
// float or double; and the baseline function that writes the records (raster/setup_simd.cpp).
// Plain data: the ISA files (setup_simd_avx2.cpp, setup_simd_avx512.cpp) fill it.
#include <cstdint>

#include "raster/setup.h"

namespace shadowlab {

// A batch's lanes between the vector code and the records: the integers as int64 (AVX-512)
// or as the doubles that hold them exactly (AVX2), the plane as float or double.
template <class Int, class Real>
struct SetupLanes {
  alignas(64) Int a[3][8], b[3][8], c[3][8], area[8], x0[8], x1[8], y0[8], y1[8];
  alignas(64) Real iw[3][8], z0[8], zx[8], zy[8], lo[8], hi[8];
};

// The records of the lanes in `live` (bit k: lane k), in lane order, to out; returns their
// number. Vertices 1 and 2 swapped where `neg`, edge e's bias 0 where top_left[e] has the lane,
// else −1 (setup_simd.cpp).
int write_setups(const SetupLanes<int64_t, float>& L, int live, int neg, const int* top_left,
                 const uint32_t* triangle, TriangleSetup* out);
int write_setups(const SetupLanes<double, double>& L, int live, int neg, const int* top_left,
                 const uint32_t* triangle, TriangleSetup* out);

}  // namespace shadowlab
