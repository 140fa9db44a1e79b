#pragma once
// ESM's log-space box filter (techniques/filters/moments_common/moment_filter.h, filter_esm_log) in float, one tile of
// 32 × 32 output texels at a time, each tile shifted by the middle of its own inputs' range.
// With lo and hi the smallest and largest finite distance the tile's windows read (its texels
// and k/2 around them, clamped at the image's edges) and s the float nearest (lo + hi)/2, a
// texel's value is
//   c·s + ln( box_k( e^(c·(d − s)) ) ),
// the same quantity as the whole-face form c·d_min + ln(box_k(e^(c·(d − d_min)))) (any shift
// gives it), but every exponent lies in [−80, 80] when X = c·max(hi − s, s − lo) <= 80 (about
// c·(hi − lo)/2): the exponentials,
// their k² sums (k <= 9: 81·e^80 < FLT_MAX) and the window means stay normal floats, so exp,
// the sums and ln run 8 or 16 lanes per instruction where the double path runs 4 or 8. A tile
// whose range is wider (a silhouette against a far background at a large c) keeps the double
// path. Both are within float precision of the exact value; the float path's bound is
// (X + 2k + 4)·2^-24 + 2.3e-7 + half the stored float's ulp (docs/techniques/esm.md
// and tests/techniques/esm_float_tiles_test.cpp).
#include <cstddef>

namespace shadowlab {

struct FaceTiles;  // techniques/pipeline/texel_tiles.h

// The largest exponent magnitude X of a tile the float path takes, and the widest
// box it takes: 81 terms of at most e^80·(1 + 2^-21) stay below FLT_MAX (3.4e38), and e^-80 is
// a normal float.
constexpr double kEsmFloatExponent = 80.0;
constexpr int kEsmFloatMaxWidth = 9;

// Filters, into out (w·h floats, row-major), the tiles of `tiles` (nullptr or every(): all
// tiles) that the float path takes, and marks in `rest` (resized to the face's tile grid,
// cleared) the ones it leaves, whose texels it does not write. Returns the number left. k odd,
// 1 <= k <= kEsmFloatMaxWidth; c > 0. simd false: the scalar kernels (the oracle), else the
// widest of AVX-512 and AVX2 the CPU has (core/isa.h: process_isa); both give the same bits.
size_t esm_float_tiles(const float* dist, int w, int h, int k, double c, bool simd,
                       const FaceTiles* tiles, float* out, FaceTiles& rest);

}  // namespace shadowlab
