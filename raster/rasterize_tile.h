#pragma once
// Back end of the rasterizer: per-tile coverage, depth test and fragment shading.
//
// Shader concept (static dispatch, no virtual calls):
//   struct Shader {
//     static constexpr bool kNeedsAttributes = ...;  // false: Fragment::bary is not filled
//     bool operator()(const Fragment& f);            // false = discard (depth not written)
//   };
// The shader runs only for fragments that pass the depth test (1/w strictly greater than the
// stored value, so of two equal depths the earlier triangle wins), and may write per-pixel
// data of its own; the last kept fragment of a pixel is the visible one.
#include <algorithm>

#include "core/parallel.h"
#include "raster/tile_binner.h"

namespace shadowlab {

// Rasterizes triangle `s` inside the pixel rectangle [x0, x1) × [y0, y1).
template <class Shader>
void rasterize_triangle_in_rect(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                DepthTarget& depth, Shader& shader) {
  const int min_x = std::max(s.min_x, x0), max_x = std::min(s.max_x, x1 - 1);
  const int min_y = std::max(s.min_y, y0), max_y = std::min(s.max_y, y1 - 1);
  if (min_x > max_x || min_y > max_y) return;
  const int64_t half = kSubpixelOne / 2;
  const int64_t px0 = int64_t(min_x) * kSubpixelOne + half;
  const int64_t py0 = int64_t(min_y) * kSubpixelOne + half;
  // Exact integer edge values at the first pixel centre, stepped per pixel and per row.
  int64_t row[3], step_x[3], step_y[3];
  for (int k = 0; k < 3; ++k) {
    row[k] = s.a[k] * px0 + s.b[k] * py0 + s.c[k] + s.bias[k];
    step_x[k] = s.a[k] * kSubpixelOne;
    step_y[k] = s.b[k] * kSubpixelOne;
  }
  // The stepped values include the fill-rule bias; barycentrics use the unbiased value (e - bias).
  const float inv_area = 1.0f / float(s.area2);
  const int width = depth.width;
  Fragment f;
  f.triangle = s.triangle;
  for (int y = min_y; y <= max_y; ++y) {
    int64_t e0 = row[0], e1 = row[1], e2 = row[2];
    float* zrow = depth.inv_w.data() + size_t(y) * size_t(width);
    for (int x = min_x; x <= max_x; ++x) {
      if ((e0 | e1 | e2) >= 0) {
        // Screen-space barycentrics of the three setup vertices.
        const float l0 = float(e0 - s.bias[0]) * inv_area;
        const float l1 = float(e1 - s.bias[1]) * inv_area;
        const float l2 = float(e2 - s.bias[2]) * inv_area;
        const float iw = l0 * s.inv_w[0] + l1 * s.inv_w[1] + l2 * s.inv_w[2];
        if (iw > zrow[x]) {
          f.x = x;
          f.y = y;
          f.inv_w = iw;
          if constexpr (Shader::kNeedsAttributes) {
            const vec3 b = l0 * s.bary_over_w[0] + l1 * s.bary_over_w[1] + l2 * s.bary_over_w[2];
            const float r = 1.0f / iw;
            f.bary[0] = b.x * r;
            f.bary[1] = b.y * r;
            f.bary[2] = b.z * r;
          }
          if (shader(f)) zrow[x] = iw;
        }
      }
      e0 += step_x[0];
      e1 += step_x[1];
      e2 += step_x[2];
    }
    row[0] += step_y[0];
    row[1] += step_y[1];
    row[2] += step_y[2];
  }
}

// Rasterizes every binned triangle into `depth` (already sized and cleared by the caller),
// tiles in parallel, each tile's triangles in submission order.
template <class Shader>
void rasterize_frame(const BinnedFrame& frame, DepthTarget& depth, Shader& shader) {
  const size_t tiles = size_t(frame.tiles_x) * size_t(frame.tiles_y);
  parallel_for(0, tiles, [&](size_t t) {
    const int tx = int(t % size_t(frame.tiles_x)), ty = int(t / size_t(frame.tiles_x));
    const int x0 = tx * kTileSize, y0 = ty * kTileSize;
    const int x1 = std::min(frame.width, x0 + kTileSize);
    const int y1 = std::min(frame.height, y0 + kTileSize);
    for (const BinnedChunk& chunk : frame.chunks)
      for (uint32_t i = chunk.offsets[t]; i < chunk.offsets[t + 1]; ++i)
        rasterize_triangle_in_rect(chunk.setups[chunk.items[i]], x0, y0, x1, y1, depth, shader);
  });
}

}  // namespace shadowlab
