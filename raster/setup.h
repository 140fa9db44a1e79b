#pragma once
// Triangle setup: snap a clipped triangle to fixed point, orient it, cull it, and derive the
// three integer edge functions with the top-left fill rule and its pixel bounding box.
#include <cstdint>

#include "raster/clip.h"
#include "raster/raster_types.h"

namespace shadowlab {

struct TriangleSetup {
  // Biased edge k (opposite vertex k) at a fixed-point sample point (px, py):
  //   E_k = a[k] * px + b[k] * py + c[k]; a pixel is covered iff E_k >= 0 for all k. c holds
  // the fill-rule bias: 0 on top and left edges and -1 otherwise (the top-left rule on exact
  // integers, so a pixel centre on an edge shared by two triangles is covered exactly once);
  // the exact edge value is E_k - bias[k].
  int64_t a[3], b[3], c[3];
  int8_t bias[3];
  int64_t area2;                 // twice the area, fixed point squared, > 0
  int min_x, min_y, max_x, max_y;  // covered-pixel bounds, inclusive, clamped to the viewport
  float inv_w[3];                // 1/w at the vertices
  // Depth plane: 1/w at pixel (x, y) is z0 + z_dx·(x − min_x) + z_dy·(y − min_y), evaluated in
  // float exactly so by every path (scalar, blocked, vectorized), which keeps them bit-equal.
  float z0, z_dx, z_dy;
  // The result is clamped to [z_lo, z_hi], the range of the vertices' 1/w: a covered pixel's
  // true value lies in it, and a sliver's ill-conditioned plane cannot run away.
  float z_lo, z_hi;
  vec3 bary_over_w[3];           // original-triangle barycentrics / w at the vertices
  uint32_t triangle;             // submission index of the original triangle
};

// Sets up one triangle of a clipped polygon. Returns false (and counts why in stats) when it
// is culled by facing or has zero area after snapping or covers no pixel centre's bounding box.
bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                    uint32_t triangle, int width, int height, CullMode cull,
                    TriangleSetup& out, RasterStats& stats);

}  // namespace shadowlab
