#pragma once
// Types shared by the rasterizer's stages.
//
// Conventions: clip space is OpenGL's (visible z in [-w, w]); screen space has its origin at the
// top-left corner, x right, y down, in pixels; pixel (x, y) has its centre at (x + 0.5, y + 0.5).
// Screen positions are snapped to fixed point with kSubpixelBits fractional bits; edge functions
// are evaluated exactly in 64-bit integers. The depth buffer stores 1/w (reciprocal view depth):
// larger is nearer, 0 means empty. 1/w is affine in screen space, so its plane is exact, and it
// keeps float precision at every distance (like reversed z).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/aligned_vector.h"

namespace shadowlab {

constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixelOne = int64_t(1) << kSubpixelBits;
// Guard band, in pixels beyond each side of the viewport: geometry is clipped in x/y only when it
// extends past it, which keeps fixed-point coordinates below 2^23 and edge products below 2^47.
constexpr double kGuardBandPixels = 16384.0;
// Tiles are square, kTileSize pixels on a side; triangles are binned to tiles in submission order.
constexpr int kTileSize = 64;

// Which triangles to drop. Front = counter-clockwise in normalized device coordinates (OpenGL).
enum class CullMode { None, Back, Front };

// Counts of what happened to the submitted triangles.
struct RasterStats {
  size_t triangles_in = 0;        // submitted
  size_t culled_frustum = 0;      // all vertices outside one frustum plane (or behind the eye)
  size_t culled_facing = 0;       // dropped by the cull mode
  size_t dropped_degenerate = 0;  // zero area after snapping (no pixels can be covered)
  size_t dropped_nonfinite = 0;   // a NaN/Inf vertex after transformation
  size_t clipped = 0;             // crossed the near plane or the guard band and were clipped
  size_t setups = 0;              // triangles that reached binning (after clipping)
  size_t fragments = 0;           // fragments that passed the depth test (filled by shaders' caller)
};

// Adds every count of s into `into` (chunks of one frame, passes over one target).
inline void add_stats(RasterStats& into, const RasterStats& s) {
  into.triangles_in += s.triangles_in;
  into.culled_frustum += s.culled_frustum;
  into.culled_facing += s.culled_facing;
  into.dropped_degenerate += s.dropped_degenerate;
  into.dropped_nonfinite += s.dropped_nonfinite;
  into.clipped += s.clipped;
  into.setups += s.setups;
  into.fragments += s.fragments;
}

// Depth target: width × height values of 1/w, row-major, y down; 0 = nothing drawn. With
// with_ids set it is also a visibility buffer: ids holds the submission index of the triangle
// whose fragment was kept last at each pixel (0xFFFFFFFF where none), written by the
// rasterizer itself so depth-only fast paths can fill it.
struct DepthTarget {
  int width = 0;
  int height = 0;
  bool with_ids = false;
  LineAlignedFloats inv_w;  // 64-byte aligned: rasterize_frame streams whole lines into it
  std::vector<uint32_t> ids;
  // Sizes the target without clearing (the rasterizer clears tile by tile).
  void resize(int w, int h) {
    width = w;
    height = h;
    inv_w.resize(size_t(w) * size_t(h));
    if (with_ids) ids.resize(size_t(w) * size_t(h));
  }
};

// What the rasterizer hands a fragment shader for a covered pixel that passed the depth test.
struct Fragment {
  int x = 0, y = 0;          // pixel
  uint32_t triangle = 0;     // index of the triangle in submission order (global over meshes)
  float bary[3] = {0, 0, 0}; // perspective-correct barycentrics w.r.t. the ORIGINAL triangle's vertices
  float inv_w = 0.0f;        // 1 / view depth
};

}  // namespace shadowlab
