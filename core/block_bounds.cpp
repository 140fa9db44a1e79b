#include "core/block_bounds.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace shadowlab {

#if defined(__x86_64__)
// The AVX2 steps (core/block_bounds_avx2.cpp).
namespace block_bounds_avx2 {
bool add_full_segment(const float* f, float* lanes);
float fold_min(const float* v, int c);
float fold_max(const float* v, int c);
}  // namespace block_bounds_avx2
#endif

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

constexpr BlockBoundsKernels kBoundsScalar{Isa::scalar, nullptr, nullptr, nullptr};
#if defined(__x86_64__)
constexpr BlockBoundsKernels kBoundsAvx2{Isa::avx2, block_bounds_avx2::add_full_segment,
                                         block_bounds_avx2::fold_min, block_bounds_avx2::fold_max};
#endif

}  // namespace

const BlockBoundsKernels& block_bounds_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa >= Isa::avx2) return kBoundsAvx2;
#endif
  (void)isa;
  return kBoundsScalar;
}

void BlockRowBounds::reset(int blocks_x) {
  kernels = &block_bounds_kernels(process_isa());
  acc.assign(size_t(blocks_x), BlockBounds{});
  nan.assign(size_t(blocks_x), 0);
  used.assign(size_t(blocks_x), 0);
  lanes.resize(size_t(blocks_x) * 48);
}

void BlockRowBounds::add_row(const vec3* pos, const uint8_t* cov, int width) {
  static_assert(sizeof(vec3) == 12, "packed vec3");
  for (size_t b = 0; b < acc.size(); ++b) {
    const int x0 = int(b) * kGBufferBlock, x1 = std::min(width, x0 + kGBufferBlock);
    if (kernels->add_full_segment && x1 - x0 == kGBufferBlock) {
      uint64_t c[2];
      std::memcpy(c, cov + x0, 16);
      if (c[0] == 0x0101010101010101ull && c[1] == 0x0101010101010101ull) {
        if (!used[b]) {
          std::fill_n(&lanes[48 * b], 24, kInf);
          std::fill_n(&lanes[48 * b + 24], 24, -kInf);
          used[b] = 1;
        }
        nan[b] |= uint8_t(kernels->add_full_segment(&pos[x0].x, &lanes[48 * b]));
        continue;
      }
    }
    vec3 lo = acc[b].lo, hi = acc[b].hi;
    bool bad = false;
    for (int x = x0; x < x1; ++x) {
      if (!cov[x]) continue;
      const vec3 p = pos[x];
      bad |= (p.x != p.x) | (p.y != p.y) | (p.z != p.z);
      for (int k = 0; k < 3; ++k) {
        lo[k] = p[k] < lo[k] ? p[k] : lo[k];
        hi[k] = p[k] > hi[k] ? p[k] : hi[k];
      }
    }
    acc[b].lo = lo;
    acc[b].hi = hi;
    nan[b] |= uint8_t(bad);
  }
}

void BlockRowBounds::store(GBuffer& g, int by) const {
  for (size_t b = 0; b < acc.size(); ++b) {
    BlockBounds out = acc[b];
    // The vector path's lanes (set only on that path). Minima and maxima of equal values are
    // order-independent except for the sign of a zero, which no consumer looks at.
    if (used[b])
      for (int c = 0; c < 3; ++c) {
        const float l = kernels->fold_min(&lanes[48 * b], c);
        const float h = kernels->fold_max(&lanes[48 * b + 24], c);
        out.lo[c] = l < out.lo[c] ? l : out.lo[c];
        out.hi[c] = h > out.hi[c] ? h : out.hi[c];
      }
    if (nan[b]) {
      out.lo = vec3(-kInf);
      out.hi = vec3(kInf);
    }
    g.block_bounds[size_t(by) * acc.size() + b] = out;
  }
}

void compute_block_bounds(GBuffer& g, int y0, int y1) {
  if (!g.has_block_bounds())
    g.block_bounds.assign(size_t(g.blocks_x()) * size_t(g.blocks_y()), BlockBounds{});
  BlockRowBounds row;
  for (int by = y0 / kGBufferBlock; by * kGBufferBlock < y1; ++by) {
    row.reset(g.blocks_x());
    const int ye = std::min(y1, (by + 1) * kGBufferBlock);
    for (int y = by * kGBufferBlock; y < ye; ++y) {
      const size_t i = size_t(y) * size_t(g.width);
      row.add_row(&g.position[i], &g.covered[i], g.width);
    }
    row.store(g, by);
  }
}

void compute_block_bounds(GBuffer& g) { compute_block_bounds(g, 0, g.height); }

}  // namespace shadowlab
