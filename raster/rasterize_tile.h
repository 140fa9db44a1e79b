#pragma once
// Back end of the rasterizer: per-tile coverage, depth test and fragment shading.
//
// Shader concept (static dispatch, no virtual calls):
//   struct Shader {
//     static constexpr bool kNeedsAttributes = ...;  // false: Fragment::bary is not filled
//     static constexpr bool kKeepsAll = ...;         // true: operator() never discards, has no
//                                                    // side effects (depth-only fast path)
//     bool operator()(const Fragment& f);            // false = discard (depth not written)
//   };
// The shader runs only for fragments that pass the depth test (1/w strictly greater than the
// stored value, so of two equal depths the earlier triangle wins), and may write per-pixel
// data of its own; the last kept fragment of a pixel is the visible one.
#include <algorithm>
#include <cstdint>

#include "core/parallel.h"
#include "core/stream_copy.h"
#include "raster/depth_kernels.h"
#include "raster/tile_binner.h"

namespace shadowlab {

// True when the shader declares kKeepsAll = true (optional; default false).
template <class Shader>
constexpr bool kKeepsAll = [] {
  if constexpr (requires { Shader::kKeepsAll; }) return bool(Shader::kKeepsAll);
  return false;
}();

// Side of the blocks of the hierarchical test: a block wholly outside one edge is skipped, a
// block wholly inside all three edges is filled without per-pixel edge tests.
constexpr int kBlockSize = 8;

// 1/w of triangle s at pixel (x, y): the one formula every path uses.
inline float plane_depth(const TriangleSetup& s, int x, int y) {
  const float zy = s.z0 + s.z_dy * float(y - s.min_y);
  return std::min(std::max(zy + s.z_dx * float(x - s.min_x), s.z_lo), s.z_hi);
}

// Depth-tests and shades one covered pixel; e0..e2 are the biased edge values there.
template <class Shader>
inline void shade_pixel(const TriangleSetup& s, int x, int y, int64_t e0, int64_t e1, int64_t e2,
                        float* zrow, uint32_t* idrow, Fragment& f, Shader& shader) {
  const float iw = plane_depth(s, x, y);
  if (!(iw > zrow[x])) return;
  f.x = x;
  f.y = y;
  f.inv_w = iw;
  if constexpr (Shader::kNeedsAttributes) {
    // Perspective-correct barycentrics from the exact (unbiased) edge values.
    const float inv_area = 1.0f / float(s.area2);
    const float l0 = float(e0 - s.bias[0]) * inv_area;
    const float l1 = float(e1 - s.bias[1]) * inv_area;
    const float l2 = float(e2 - s.bias[2]) * inv_area;
    const vec3 b = l0 * s.bary_over_w[0] + l1 * s.bary_over_w[1] + l2 * s.bary_over_w[2];
    const float d = l0 * s.inv_w[0] + l1 * s.inv_w[1] + l2 * s.inv_w[2];
    const float r = 1.0f / d;
    f.bary[0] = b.x * r;
    f.bary[1] = b.y * r;
    f.bary[2] = b.z * r;
  }
  if (shader(f)) {
    zrow[x] = iw;
    if (idrow) idrow[x] = s.triangle;
  }
}

// Depth-only shaders (kKeepsAll, no attributes): triangle `s` inside the rectangle
// [x0, x1) × [y0, y1) (a tile) as whole 8×8 blocks through the SIMD kernel, one call per row of
// blocks (depth_row8: the walk from block to block in the kernel's registers). Same coverage
// and depth as the generic path, pixel for pixel.
// The storage is a view: pixel (x, y)'s 1/w at z[y · width + x] and its id at ids[y · width + x]
// (ids null: none kept), the whole target's or a tile-local buffer's (rasterize_frame).
inline void rasterize_depth_in_rect(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                    float* z, uint32_t* ids, size_t width) {
  const int min_x = std::max(s.min_x, x0), max_x = std::min(s.max_x, x1 - 1);
  const int min_y = std::max(s.min_y, y0), max_y = std::min(s.max_y, y1 - 1);
  if (min_x > max_x || min_y > max_y) return;
  static const DepthTriangleFn whole = depth_kernels(process_isa()).triangle;
  if (whole) {
    whole(s, x0, y0, x1, y1, z, ids, width);
    return;
  }
  const int64_t half = kSubpixelOne / 2;
  DepthRow8 row;
  int64_t x_span[3];
  for (int k = 0; k < 3; ++k) {
    row.step_x[k] = s.a[k] * kSubpixelOne;
    row.step_y[k] = s.b[k] * kSubpixelOne;
    row.block_step[k] = row.step_x[k] * kBlockSize;
    x_span[k] = row.step_x[k] * (kBlockSize - 1);
  }
  row.z0 = s.z0;
  row.z_dx = s.z_dx;
  row.z_dy = s.z_dy;
  row.z_lo = s.z_lo;
  row.z_hi = s.z_hi;
  row.id = s.triangle;
  const int bx_start = min_x - (min_x - x0) % kBlockSize;
  const int by_start = min_y - (min_y - y0) % kBlockSize;
  // Blocks of a row, and whether the last one is cut by the viewport's right edge (x1 not a
  // multiple of 8 from the tile's origin): that one goes pixel by pixel.
  const int blocks = (max_x - bx_start) / kBlockSize + 1;
  const bool cut = bx_start + kBlockSize * blocks > x1;
  row.blocks = blocks - (cut ? 1 : 0);
  row.ox = bx_start - s.min_x;
  for (int by = by_start; by <= max_y; by += kBlockSize) {
    const int py0 = std::max(by, min_y), py1 = std::min(by + kBlockSize - 1, max_y);
    row.oy = py0 - s.min_y;
    row.rows = py1 - py0 + 1;
    for (int k = 0; k < 3; ++k) {
      row.edge[k] = s.a[k] * (int64_t(bx_start) * kSubpixelOne + half) +
                    s.b[k] * (int64_t(py0) * kSubpixelOne + half) + s.c[k];
      const int64_t dy = row.step_y[k] * int64_t(py1 - py0);
      row.lo_off[k] = std::min<int64_t>(0, x_span[k]) + std::min<int64_t>(0, dy);
      row.hi_off[k] = std::max<int64_t>(0, x_span[k]) + std::max<int64_t>(0, dy);
    }
    float* zrow = z + size_t(py0) * width;
    uint32_t* idrow = ids ? ids + size_t(py0) * width : nullptr;
    row.ids = idrow ? idrow + bx_start : nullptr;
    if (row.blocks > 0) depth_row8(row, zrow + bx_start, width);
    if (!cut) continue;
    // The block cut by the viewport's right edge: pixel by pixel.
    const int bx = bx_start + kBlockSize * row.blocks;
    int64_t e[3];
    for (int k = 0; k < 3; ++k) e[k] = row.edge[k] + row.block_step[k] * row.blocks;
    if (e[0] + row.hi_off[0] < 0 || e[1] + row.hi_off[1] < 0 || e[2] + row.hi_off[2] < 0)
      continue;
    for (int y = py0; y <= py1; ++y)
      for (int x = bx; x < x1; ++x) {
        const int64_t dx = int64_t(x - bx), dy = int64_t(y - py0);
        const int64_t e0 = e[0] + row.step_x[0] * dx + row.step_y[0] * dy;
        const int64_t e1 = e[1] + row.step_x[1] * dx + row.step_y[1] * dy;
        const int64_t e2 = e[2] + row.step_x[2] * dx + row.step_y[2] * dy;
        if ((e0 | e1 | e2) < 0) continue;
        const float iw = plane_depth(s, x, y);
        float& zp = z[size_t(y) * width + size_t(x)];
        if (iw > zp) {
          zp = iw;
          if (ids) ids[size_t(y) * width + size_t(x)] = s.triangle;
        }
      }
  }
}

inline void rasterize_depth_in_rect(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                    DepthTarget& depth) {
  rasterize_depth_in_rect(s, x0, y0, x1, y1, depth.inv_w.data(),
                          depth.with_ids ? depth.ids.data() : nullptr, size_t(depth.width));
}

// Rasterizes triangle `s` inside the pixel rectangle [x0, x1) × [y0, y1) (a tile, whose origin
// is a multiple of kBlockSize), block by block, pixel by pixel inside a block: the general
// path (any shader) and the scalar reference of rasterize_depth_in_rect.
template <class Shader>
void rasterize_triangle_in_rect(const TriangleSetup& s, int x0, int y0, int x1, int y1,
                                DepthTarget& depth, Shader& shader) {
  const int min_x = std::max(s.min_x, x0), max_x = std::min(s.max_x, x1 - 1);
  const int min_y = std::max(s.min_y, y0), max_y = std::min(s.max_y, y1 - 1);
  if (min_x > max_x || min_y > max_y) return;
  const int64_t half = kSubpixelOne / 2;
  const int width = depth.width;
  Fragment f;
  f.triangle = s.triangle;
  // Exact biased edge value at pixel (x, y).
  auto edge = [&](int k, int x, int y) {
    return s.a[k] * (int64_t(x) * kSubpixelOne + half) + s.b[k] * (int64_t(y) * kSubpixelOne + half) +
           s.c[k];
  };
  const int bx_start = min_x - (min_x - x0) % kBlockSize;
  const int by_start = min_y - (min_y - y0) % kBlockSize;
  for (int by = by_start; by <= max_y; by += kBlockSize) {
    const int py0 = std::max(by, min_y), py1 = std::min(by + kBlockSize - 1, max_y);
    for (int bx = bx_start; bx <= max_x; bx += kBlockSize) {
      const int px0 = std::max(bx, min_x), px1 = std::min(bx + kBlockSize - 1, max_x);
      // Edge extremes over the block's pixel centres (edges are linear: corners suffice).
      bool outside = false, inside = true;
      int64_t e_origin[3];
      for (int k = 0; k < 3; ++k) {
        const int64_t e = edge(k, px0, py0);
        e_origin[k] = e;
        const int64_t dx = s.a[k] * int64_t(px1 - px0) * kSubpixelOne;
        const int64_t dy = s.b[k] * int64_t(py1 - py0) * kSubpixelOne;
        const int64_t lo = e + std::min<int64_t>(0, dx) + std::min<int64_t>(0, dy);
        const int64_t hi = e + std::max<int64_t>(0, dx) + std::max<int64_t>(0, dy);
        outside = outside || hi < 0;
        inside = inside && lo >= 0;
      }
      if (outside) continue;
      const int64_t step_x[3] = {s.a[0] * kSubpixelOne, s.a[1] * kSubpixelOne, s.a[2] * kSubpixelOne};
      const int64_t step_y[3] = {s.b[0] * kSubpixelOne, s.b[1] * kSubpixelOne, s.b[2] * kSubpixelOne};
      int64_t row[3] = {e_origin[0], e_origin[1], e_origin[2]};
      for (int y = py0; y <= py1;
           ++y, row[0] += step_y[0], row[1] += step_y[1], row[2] += step_y[2]) {
        float* zrow = depth.inv_w.data() + size_t(y) * size_t(width);
        uint32_t* idrow = depth.with_ids ? depth.ids.data() + size_t(y) * size_t(width) : nullptr;
        int64_t e0 = row[0], e1 = row[1], e2 = row[2];
        for (int x = px0; x <= px1; ++x) {
          if (inside || (e0 | e1 | e2) >= 0) shade_pixel(s, x, y, e0, e1, e2, zrow, idrow, f, shader);
          e0 += step_x[0];
          e1 += step_x[1];
          e2 += step_x[2];
        }
      }
    }
  }
}

// Shaders may also define `void finish_tile(int x0, int y0, int x1, int y1, float* z,
// size_t stride)`, called once per tile after its last triangle while the tile is still in cache
// (e.g. to turn 1/w into stored shadow-map values): pixel (x, y)'s value is z[y · stride + x],
// in the target itself or in the tile-local buffer (rasterize_frame), which rasterize_frame then
// copies into the target.
template <class Shader>
concept HasFinishTile = requires(Shader& s, float* z) { s.finish_tile(0, 0, 0, 0, z, size_t(0)); };

// Pixel (x, y) of the tile whose corner is (x0, y0) at origin[y · kTileSize + x] for a tile-local
// buffer `tile` of kTileSize² values: the origin is the address kTileSize · y0 + x0 floats before
// the buffer, formed as an integer because it lies outside it (only addresses inside it are
// read or written). The kernels then address the buffer with the target's own coordinates.
inline float* tile_origin(float* tile, int x0, int y0) {
  const size_t before = (size_t(y0) * size_t(kTileSize) + size_t(x0)) * sizeof(float);
  return reinterpret_cast<float*>(reinterpret_cast<uintptr_t>(tile) - before);
}

// Rasterizes every binned triangle into `depth` (sized by the caller; with `clear`, each tile
// clears its own pixels first, while they are in cache; without, it draws over what an earlier
// pass left), tiles in parallel, each tile's triangles in submission order.
constexpr uint32_t kPrefetchAhead = 4;  // items ahead whose setup rasterize_frame prefetches
// Targets from this size on (a 2048 × 1024 face and up) are drawn tile by tile in a tile-local
// buffer and streamed into place (rasterize_frame).
constexpr size_t kStreamedTargetBytes = size_t(8) << 20;

// Calls fn(setup) for every triangle binned to tile t, chunk by chunk in submission order,
// prefetching the setup kPrefetchAhead items on: the records (~176 bytes, three cache lines) are
// read in tile order, scattered over the chunk, and a first read of one missed the caches (the
// largest stall of the depth walk's profile). A hint: no value changes.
template <class Fn>
inline void for_each_tile_setup(const BinnedFrame& frame, size_t t, Fn&& fn) {
  for (const BinnedChunk& chunk : frame.chunks) {
    const uint32_t end = chunk.offsets[t + 1];
    for (uint32_t i = chunk.offsets[t]; i < end; ++i) {
      if (i + kPrefetchAhead < end) {
        const char* next = reinterpret_cast<const char*>(&chunk.setups[chunk.items[i + kPrefetchAhead]]);
        for (size_t line = 0; line < sizeof(TriangleSetup); line += 64) __builtin_prefetch(next + line);
      }
      fn(chunk.setups[chunk.items[i]]);
    }
  }
}

template <class Shader>
void rasterize_frame(const BinnedFrame& frame, DepthTarget& depth, Shader& shader,
                     bool clear = true) {
  const size_t tiles = size_t(frame.tiles_x) * size_t(frame.tiles_y);
  // Depth-only shaders on a cleared target without ids draw each tile into a tile-local buffer (16
  // KB, in L1) and copy it into the target at the end with non-temporal stores
  // (core/stream_copy.h): the target's lines are then written without first being read, where
  // clearing them in place read every line of the target from memory (docs/performance_history.md).
  // The same operations on the same values: the same bits. Only where every tile row starts on a
  // 64-byte line (a 64-byte aligned target, rows a multiple of 16 floats): partial lines written
  // non-temporally measured slower than clearing in place. And only for targets of
  // kStreamedTargetBytes or more: non-temporal stores leave the target in memory, not in the
  // caches, and a smaller target is read back soon (the lookup after a cube of 1024² faces, 24 MB,
  // took 13 % longer while the render gained 9 %; at 2048², 96 MB, nothing of it stays cached
  // either way).
  constexpr bool kDepthOnly = !Shader::kNeedsAttributes && kKeepsAll<Shader>;
  const bool local = kDepthOnly && clear && !depth.with_ids && depth.width % 16 == 0 &&
                     reinterpret_cast<uintptr_t>(depth.inv_w.data()) % 64 == 0 &&
                     depth.inv_w.size() * sizeof(float) >= kStreamedTargetBytes;
  static const StreamCopy copy = stream_copy_kernel();
  parallel_for(0, tiles, [&](size_t t) {
    const int tx = int(t % size_t(frame.tiles_x)), ty = int(t / size_t(frame.tiles_x));
    const int x0 = tx * kTileSize, y0 = ty * kTileSize;
    const int x1 = std::min(frame.width, x0 + kTileSize);
    const int y1 = std::min(frame.height, y0 + kTileSize);
    if constexpr (kDepthOnly) {
      if (local) {
        alignas(64) float tile[kTileSize * kTileSize];
        for (int y = 0; y < y1 - y0; ++y) std::fill_n(tile + y * kTileSize, x1 - x0, 0.0f);
        float* const origin = tile_origin(tile, x0, y0);
        for_each_tile_setup(frame, t, [&](const TriangleSetup& s) {
          rasterize_depth_in_rect(s, x0, y0, x1, y1, origin, nullptr, size_t(kTileSize));
        });
        if constexpr (HasFinishTile<Shader>) shader.finish_tile(x0, y0, x1, y1, origin, size_t(kTileSize));
        for (int y = y0; y < y1; ++y)
          copy(tile + (y - y0) * kTileSize, size_t(x1 - x0),
               depth.inv_w.data() + size_t(y) * size_t(depth.width) + x0);
        stream_fence();  // the copies' stores before the tile is done (core/stream_copy.h)
        return;
      }
    }
    for (int y = y0; y < y1 && clear; ++y) {
      std::fill_n(depth.inv_w.data() + size_t(y) * size_t(depth.width) + x0, x1 - x0, 0.0f);
      if (depth.with_ids)
        std::fill_n(depth.ids.data() + size_t(y) * size_t(depth.width) + x0, x1 - x0, 0xFFFFFFFFu);
    }
    for_each_tile_setup(frame, t, [&](const TriangleSetup& s) {
      if constexpr (kDepthOnly)
        rasterize_depth_in_rect(s, x0, y0, x1, y1, depth);
      else
        rasterize_triangle_in_rect(s, x0, y0, x1, y1, depth, shader);
    });
    if constexpr (HasFinishTile<Shader>)
      shader.finish_tile(x0, y0, x1, y1, depth.inv_w.data(), size_t(depth.width));
  });
}

}  // namespace shadowlab
