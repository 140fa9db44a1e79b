#pragma once
// GBuffer::block_bounds: per 16×16 block of the image, the bounds of its covered pixels'
// positions. The camera pass accumulates them row by row while it writes the rows
// (BlockRowBounds); compute_block_bounds recomputes them from a finished GBuffer.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"

namespace shadowlab {

// One block row's bounds, accumulated image row by image row, then stored.
//
// A 16-pixel segment of a row is 48 packed floats, six 8-float vectors in which lane k of
// vector j holds component (8j + k) mod 3 of its pixel: vectors j and j + 3 share that pattern,
// so fully covered segments update three minimum and three maximum vectors per block with no
// shuffles (the AVX2 path), and `store` folds the lanes into x, y and z. Segments with
// uncovered pixels, and every segment on the scalar path, go pixel by pixel into the same
// minima and maxima: min and max are exact, so both paths give the same bits.
struct BlockRowBounds {
  std::vector<BlockBounds> acc;  // per block: pixel-by-pixel minima and maxima
  std::vector<float> lanes;      // per block: 6 × 8 floats (3 minimum, 3 maximum vectors)
  std::vector<uint8_t> nan;      // per block: a NaN position was added
  std::vector<uint8_t> used;     // per block: `lanes` holds values (else it is unset)
  bool avx2 = false;             // process_isa() >= Isa::avx2 at reset
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
