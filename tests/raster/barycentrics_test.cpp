// Fragment::bary, the perspective-correct barycentrics that attribute shaders (the alpha test's
// texture coordinates) read: checked at every shaded pixel against the exact point of the
// original triangle that the pixel centre's ray meets, solved in long double from the clip
// positions alone (independent of snapping order, edge functions and clipping).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "raster/pipeline.h"

namespace shadowlab {
namespace {

constexpr int kBarySize = 64;

// clip = (x, y, z / 2, z): positions are given as (X·w, Y·w, w) with NDC (X, Y) and w > 0 in
// front; every product is exact, so a vertex placed on the 1/256-pixel grid stays on it.
mat4 plain_projection() {
  mat4 m(0.0f);
  m[0][0] = 1.0f;
  m[1][1] = 1.0f;
  m[2][2] = 0.5f;
  m[2][3] = 1.0f;
  return m;
}

// The position of screen point (sx, sy) (pixels, y down) at clip w.
vec3 at_screen(double sx, double sy, float w) {
  const float X = float(sx / kBarySize * 2.0 - 1.0), Y = float(1.0 - sy / kBarySize * 2.0);
  return vec3(X * w, Y * w, w);
}

struct BaryFragment {
  int x, y;
  float bary[3];
  float inv_w;
};

struct BaryShader {
  static constexpr bool kNeedsAttributes = true;
  std::vector<BaryFragment>* out;
  bool operator()(const Fragment& f) {
    out->push_back({f.x, f.y, {f.bary[0], f.bary[1], f.bary[2]}, f.inv_w});
    return false;  // keep nothing: no fragment hides another
  }
};

std::vector<BaryFragment> shade(const std::vector<vec3>& tri) {
  const uint32_t idx[3] = {0, 1, 2};
  const std::vector<MeshView> views = {{tri.data(), 3, idx, 1}};
  std::vector<BaryFragment> got;
  BaryShader shader{&got};
  DepthTarget depth;
  rasterize(views, plain_projection(), CullMode::None, kBarySize, kBarySize, depth, shader);
  return got;
}

// The barycentrics b (sum 1) of the original triangle's point that projects to the pixel centre:
// Σ b_i (x_i − X w_i) = 0, Σ b_i (y_i − Y w_i) = 0, Σ b_i = 1, by Cramer's rule.
void exact_bary(const std::vector<vec3>& tri, int px, int py, long double b[3]) {
  const mat4 m = plain_projection();
  const long double X = (px + 0.5L) / kBarySize * 2 - 1, Y = 1 - (py + 0.5L) / kBarySize * 2;
  long double r0[3], r1[3];
  for (int i = 0; i < 3; ++i) {
    const vec4 c = m * vec4(tri[i], 1.0f);
    r0[i] = (long double)c.x - X * c.w;
    r1[i] = (long double)c.y - Y * c.w;
  }
  auto det = [](const long double a[3], const long double b_[3], const long double c[3]) {
    return a[0] * (b_[1] * c[2] - b_[2] * c[1]) - a[1] * (b_[0] * c[2] - b_[2] * c[0]) +
           a[2] * (b_[0] * c[1] - b_[1] * c[0]);
  };
  const long double ones[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
  // Columns are the unknowns b_0..b_2; rows the three equations.
  const long double c0[3] = {r0[0], r1[0], 1}, c1[3] = {r0[1], r1[1], 1}, c2[3] = {r0[2], r1[2], 1};
  const long double rhs[3] = {zero[0], zero[1], ones[0]};
  const long double d = det(c0, c1, c2);
  b[0] = det(rhs, c1, c2) / d;
  b[1] = det(c0, rhs, c2) / d;
  b[2] = det(c0, c1, rhs) / d;
}

// Largest |bary − exact| over the shaded pixels, and the largest relative error of 1/w
// (1 / Σ b_i w_i). A NaN error is kept (std::max would drop it and pass a NaN barycentric).
double worst_error(const std::vector<vec3>& tri, const std::vector<BaryFragment>& got, double* worst_inv_w) {
  double worst = 0.0;
  *worst_inv_w = 0.0;
  for (const BaryFragment& s : got) {
    long double b[3];
    exact_bary(tri, s.x, s.y, b);
    long double w = 0;
    for (int i = 0; i < 3; ++i) {
      const double e = double(std::fabs(s.bary[i] - b[i]));
      if (!(e <= worst)) worst = e;
      w += b[i] * tri[i].z;
    }
    const long double inv_w = 1 / w;
    const double e = double(std::fabs(s.inv_w - inv_w) / inv_w);
    if (!(e <= *worst_inv_w)) *worst_inv_w = e;
  }
  return worst;
}

// A large triangle with vertices on the sub-pixel grid at w = 1, 2 and 4: every shaded pixel's
// barycentrics and 1/w are the exact ones to float rounding (measured 1.1e-7 and 1.6e-7).
TEST(Barycentrics, PerspectiveCorrectAtEveryPixel) {
  const std::vector<vec3> tri = {at_screen(5.25, 3.5, 1.0f), at_screen(60.0, 20.75, 2.0f),
                                 at_screen(12.5, 58.0, 4.0f)};
  // Each vertex order (the rasterizer reorients clockwise input) and both windings.
  const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (const auto& o : orders) {
    const std::vector<vec3> t = {tri[o[0]], tri[o[1]], tri[o[2]]};
    const std::vector<BaryFragment> got = shade(t);
    ASSERT_GT(got.size(), 1000u);
    double inv_w_err;
    EXPECT_LT(worst_error(t, got, &inv_w_err), 1e-6) << o[0] << o[1] << o[2];
    EXPECT_LT(inv_w_err, 1e-6);
  }
}

// Triangles of one or two pixels: the fill-rule bias (one unit of the 2^-16 px² edge
// function) is then 4e-6 of a barycentric and must not be in the weights; random grid vertices
// at random depths, so every edge of the oriented triangle is sometimes a right or bottom one.
TEST(Barycentrics, SmallTrianglesUseTheUnbiasedEdgeValues) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> sub(-300, 300);
  std::uniform_int_distribution<int> depth(0, 3);
  int shaded = 0;
  for (int t = 0; t < 400; ++t) {
    const double cx = 10.5 + t % 40, cy = 10.5 + t / 40 * 4;
    std::vector<vec3> tri;
    for (int k = 0; k < 3; ++k)
      tri.push_back(at_screen(cx + sub(rng) / 256.0, cy + sub(rng) / 256.0, float(1 << depth(rng))));
    const std::vector<BaryFragment> got = shade(tri);
    shaded += int(got.size());
    double inv_w_err;
    EXPECT_LT(worst_error(tri, got, &inv_w_err), 1e-6) << "triangle " << t;
    EXPECT_LT(inv_w_err, 1e-6) << "triangle " << t;
  }
  EXPECT_GT(shaded, 100);  // 143 pixels of 135 triangles
}

// A triangle crossing the near plane (one vertex behind the camera): the pixels see the
// clipped polygon, whose new vertices carry interpolated barycentrics of the original triangle.
// Measured error 1.6e-7 (bary) and 2.5e-7 (1/w).
TEST(Barycentrics, ClippedTrianglesKeepTheOriginalTrianglesWeights) {
  const std::vector<vec3> tri = {at_screen(8.0, 8.0, 1.0f), at_screen(56.0, 16.0, 1.0f),
                                 vec3(0.1f, -0.2f, -1.0f)};
  for (int r = 0; r < 3; ++r) {
    const std::vector<vec3> t = {tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]};
    const std::vector<BaryFragment> got = shade(t);
    ASSERT_GT(got.size(), 500u);
    double inv_w_err;
    EXPECT_LT(worst_error(t, got, &inv_w_err), 1e-6) << "rotation " << r;
    EXPECT_LT(inv_w_err, 1e-6) << "rotation " << r;
  }
}

}  // namespace
}  // namespace shadowlab
