#include "raster/setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace shadowlab {
namespace {

// Floor division for a positive divisor.
int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

}  // namespace

bool setup_triangle(const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                    uint32_t triangle, int width, int height, CullMode cull,
                    TriangleSetup& out, RasterStats& stats) {
  const ClipVertex* v[3] = {&v0, &v1, &v2};
  int64_t fx[3], fy[3];
  double sxy[3][2];  // unsnapped screen positions, for the depth plane
  for (int i = 0; i < 3; ++i) {
    // Viewport transform in double, then round to the fixed-point grid. y flips: NDC y up,
    // screen y down.
    const double inv_w = 1.0 / double(v[i]->clip.w);  // one divide per vertex
    const double sx = (double(v[i]->clip.x) * inv_w * 0.5 + 0.5) * double(width);
    const double sy = (0.5 - double(v[i]->clip.y) * inv_w * 0.5) * double(height);
    sxy[i][0] = sx;
    sxy[i][1] = sy;
    fx[i] = std::llrint(sx * double(kSubpixelOne));
    fy[i] = std::llrint(sy * double(kSubpixelOne));
  }
  // Twice the signed area in y-down screen space. Counter-clockwise in NDC (front-facing)
  // gives a negative value here because of the y flip.
  int64_t area2 = (fx[1] - fx[0]) * (fy[2] - fy[0]) - (fy[1] - fy[0]) * (fx[2] - fx[0]);
  if (area2 == 0) {
    ++stats.dropped_degenerate;
    return false;
  }
  const bool front = area2 < 0;
  if ((cull == CullMode::Back && !front) || (cull == CullMode::Front && front)) {
    ++stats.culled_facing;
    return false;
  }
  int order[3] = {0, 1, 2};
  if (area2 < 0) {
    std::swap(order[1], order[2]);
    area2 = -area2;
  }
  int64_t x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = fx[order[i]];
    y[i] = fy[order[i]];
    const ClipVertex& cv = *v[order[i]];
    out.inv_w[i] = 1.0f / cv.clip.w;
    out.bary_over_w[i] = cv.bary * out.inv_w[i];
  }
  // Edge k runs from vertex k+1 to vertex k+2 (opposite vertex k); with area2 > 0 every edge
  // function is positive inside. In y-down screen space with this orientation a "top" edge is
  // horizontal with dx > 0 and a "left" edge has dy < 0.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int64_t dx = x[j] - x[i], dy = y[j] - y[i];
    out.a[k] = -dy;
    out.b[k] = dx;
    const bool top_left = (dy == 0 && dx > 0) || dy < 0;
    out.bias[k] = int8_t(top_left ? 0 : -1);
    out.c[k] = dy * x[i] - dx * y[i] + out.bias[k];
  }
  out.area2 = area2;
  const int64_t half = kSubpixelOne / 2;
  const int64_t lo_x = std::min({x[0], x[1], x[2]}), hi_x = std::max({x[0], x[1], x[2]});
  const int64_t lo_y = std::min({y[0], y[1], y[2]}), hi_y = std::max({y[0], y[1], y[2]});
  // Pixel x covers sample 256*x + 128; keep pixels whose centre lies within the bounds.
  out.min_x = int(std::max<int64_t>(0, ceil_div(lo_x - half, kSubpixelOne)));
  out.max_x = int(std::min<int64_t>(width - 1, floor_div(hi_x - half, kSubpixelOne)));
  out.min_y = int(std::max<int64_t>(0, ceil_div(lo_y - half, kSubpixelOne)));
  out.max_y = int(std::min<int64_t>(height - 1, floor_div(hi_y - half, kSubpixelOne)));
  out.triangle = triangle;
  // No pixel centre inside the bounds (most sub-pixel triangles of dense meshes): done before
  // the depth plane's arithmetic.
  if (out.min_x > out.max_x || out.min_y > out.max_y) {
    ++stats.dropped_degenerate;
    return false;
  }
  {
    // Plane of 1/w through the three vertices at their UNSNAPPED screen positions, in double.
    // Coverage uses the snapped ones (watertightness); depth does not need to, and snapping a
    // vertex near the horizon by 1/512 pixel would tilt a steep 1/w plane by ~1e-3 relative.
    const double* p0 = sxy[order[0]];
    const double* p1 = sxy[order[1]];
    const double* p2 = sxy[order[2]];
    const double x10 = p1[0] - p0[0], y10 = p1[1] - p0[1];
    const double x20 = p2[0] - p0[0], y20 = p2[1] - p0[1];
    const double z10 = double(out.inv_w[1]) - out.inv_w[0], z20 = double(out.inv_w[2]) - out.inv_w[0];
    const double det = x10 * y20 - y10 * x20;
    // det can only vanish when the snapped area does not (a sliver rounding to non-zero area):
    // fall back to a constant plane then.
    const double dzdx = det != 0.0 ? (z10 * y20 - z20 * y10) / det : 0.0;  // per pixel
    const double dzdy = det != 0.0 ? (z20 * x10 - z10 * x20) / det : 0.0;
    const double px = double(out.min_x) + 0.5 - p0[0];
    const double py = double(out.min_y) + 0.5 - p0[1];
    out.z0 = float(double(out.inv_w[0]) + dzdx * px + dzdy * py);
    out.z_dx = float(dzdx);
    out.z_dy = float(dzdy);
    out.z_lo = std::min({out.inv_w[0], out.inv_w[1], out.inv_w[2]});
    out.z_hi = std::max({out.inv_w[0], out.inv_w[1], out.inv_w[2]});
  }
  return true;
}

}  // namespace shadowlab
