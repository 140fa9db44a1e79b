#pragma once
// GBuffer::block_bounds: per 16×16 block of the image, the bounds of its covered pixels'
// positions. The camera pass accumulates them row by row while it writes the rows
// (BlockRowBounds); compute_block_bounds recomputes them from a finished GBuffer.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/isa.h"

namespace shadowlab {

// The vector steps of BlockRowBounds per instruction set (docs/simd.md). The scalar table has no
// vector steps (nullptr: every segment goes pixel by pixel, the oracle); the AVX2 table's are in
// core/block_bounds_avx2.cpp, and AVX-512 uses the AVX2 table (a block row is 16 pixels: one
// segment is six AVX2 vectors).
struct BlockBoundsKernels {
  Isa isa;  // the instruction set the steps were compiled for
  // A fully covered 16-pixel segment (48 floats at f) into the block's six vectors `lanes`
  // (3 minimum, then 3 maximum vectors of 8); returns true when a float is NaN.
  bool (*add_full_segment)(const float* f, float* lanes);
  // The minimum (maximum) over the 24 floats of three minimum (maximum) vectors v whose
  // component is c (lane k of vector j holds component (8j + k) mod 3).
  float (*fold_min)(const float* v, int c);
  float (*fold_max)(const float* v, int c);
};
const BlockBoundsKernels& block_bounds_kernels(Isa isa);

// One block row's bounds, accumulated image row by image row, then stored.
//
// A 16-pixel segment of a row is 48 packed floats, six 8-float vectors in which lane k of
// vector j holds component (8j + k) mod 3 of its pixel: vectors j and j + 3 share that pattern,
// so fully covered segments update three minimum and three maximum vectors per block with no
// shuffles (the AVX2 path), and `store` folds the lanes into x, y and z. Segments with
// uncovered pixels, and every segment on the scalar table, go pixel by pixel into the same
// minima and maxima: min and max are exact, so both paths give the same bits.
struct BlockRowBounds {
  std::vector<BlockBounds> acc;  // per block: pixel-by-pixel minima and maxima
  std::vector<float> lanes;      // per block: 6 × 8 floats (3 minimum, 3 maximum vectors)
  std::vector<uint8_t> nan;      // per block: a NaN position was added
  std::vector<uint8_t> used;     // per block: `lanes` holds values (else it is unset)
  // process_isa()'s table at reset.
  const BlockBoundsKernels* kernels = &block_bounds_kernels(Isa::scalar);
  void reset(int blocks_x);
  // Adds the covered pixels of one image row: positions pos[0..width), coverage cov[0..width).
  void add_row(const vec3* pos, const uint8_t* cov, int width);
  // Writes block row `by` of g.block_bounds (sized already). A NaN position makes its block
  // undecidable from its bounds, ±inf (the consumers then walk its pixels; an infinite
  // position reaches the bounds through min and max anyway).
  void store(GBuffer& g, int by) const;
};

// Computes block_bounds for the block rows covering image rows [y0, y1) (y0 a multiple of
// kGBufferBlock; y1 one too, or the height), sizing block_bounds first if needed (not
// thread-safe then: size it before running block rows in parallel, as render_gbuffer does).
void compute_block_bounds(GBuffer& g, int y0, int y1);
// All block rows.
void compute_block_bounds(GBuffer& g);

}  // namespace shadowlab
