#pragma once
// The kernels of ESM's float tiles (techniques/filters/esm/esm_float_tiles.h) as a kernel family
// (docs/simd.md): staging a band's input rows as finite distances, a tile's exponentials, its
// inputs' range, and a whole 32-wide tile's box sums straight into the logarithm. The scalar
// table is the oracle (the tile's box and logarithm there are esm_float_tiles.cpp's loops, which
// also take the image's narrower last tiles: its box_tile is nullptr); the AVX2 and AVX-512
// tables give its bits (the same float operations in the same order, core/exp_log.h's vector
// exp and log), which tests/techniques/esm_float_tiles_test.cpp checks for every set the CPU
// runs.
#include <cstddef>

#include "core/isa.h"

namespace shadowlab {

// A tile's exponentials: rows of kEsmTilePitch floats (32 + k − 1 values each, its windows'
// inputs), computed over whole vectors; the lanes past a row's inputs are never summed.
constexpr int kEsmTilePitch = 48;  // >= 32 + kEsmFloatMaxWidth − 1, a multiple of 16
constexpr int kEsmTileWidth = 32;  // kTexelTile (techniques/pipeline/texel_tiles.h)

// ln 2 split for the stored value (esm_float_tiles.cpp, stored_value): kEsmLn2Hi12 = 2839/4096,
// so that e·kEsmLn2Hi12 is exact for |e| <= 127, and the rest.
constexpr float kEsmLn2Hi12 = 2839.0f / 4096.0f;
constexpr float kEsmLn2Lo12 = float(0.6931471805599453 - 2839.0 / 4096.0);

// dst[lead + x] = min(src[x], 1) for x < n (NaN and +inf give 1), dst[0 .. lead) = dst[lead],
// dst[lead + n .. pad_to) = dst[lead + n − 1].
using EsmStageRowFn = void (*)(const float* src, int n, int lead, int pad_to, float* dst);
// dst[yy·kEsmTilePitch + x] = exp_f(float(c·(d − s))), d = src[yy·pitch + x], for x < n (the
// vector forms also fill the lanes up to the next 8: src holds finite values there) and yy <
// rows. in_float: the exponent may be formed as c ⊗ (d ⊖ s) in float, which gives the same
// bits (esm_float_tiles.cpp, in_float_exponent); the scalar table always takes the double form.
using EsmExpRowsFn = void (*)(const float* src, size_t pitch, int rows, int n, double c,
                              double s, bool in_float, float* dst);
// lo = min(lo, every value), hi = max(hi, every value) of rows × n values at src (pitch apart).
using EsmRangeFn = void (*)(const float* src, size_t pitch, int rows, int n, float& lo,
                            float& hi);
// A whole tile (32 columns, th rows): hbuf's horizontal sums of k exponentials, each output
// row's mean × 1/k² and its stored value t_hi + e·kEsmLn2Hi12 + ((t_lo + e·kEsmLn2Lo12) + ln m)
// into out (rows w apart).
using EsmBoxTileFn = void (*)(const float* ebuf, int th, int k, float t_hi, float t_lo,
                              float* hbuf, float* out, int w);

struct EsmTileKernels {
  Isa isa;  // the instruction set of the widest kernel in the table
  EsmStageRowFn stage_row;
  EsmExpRowsFn exp_rows;
  EsmRangeFn range;
  EsmBoxTileFn box_tile;  // nullptr: the caller's scalar loops
};
const EsmTileKernels& esm_tile_kernels(Isa isa);

}  // namespace shadowlab
