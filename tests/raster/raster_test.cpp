// Rasterizer conformance: watertightness under the top-left rule, clipping, degenerate and
// non-finite input, and thread-count determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/parallel.h"
#include "raster/pipeline.h"
#include "raster/tile_binner.h"

namespace shadowlab {
namespace {

// Counts every covered pixel and discards, so the depth test never hides double coverage.
struct CountingShader {
  static constexpr bool kNeedsAttributes = true;
  int width;
  std::vector<int>* counts;
  bool operator()(const Fragment& f) {
    ++(*counts)[size_t(f.y) * width + f.x];
    return false;
  }
};

struct Soup {
  std::vector<vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<MeshView> views() const {
    return {{positions.data(), positions.size(), indices.data(), indices.size() / 3}};
  }
};

// NDC position of a screen point (pixels, y down) for a w × h viewport, identity transform.
vec3 ndc(double sx, double sy, int w, int h) {
  return vec3(float(sx / w * 2.0 - 1.0), float(1.0 - sy / h * 2.0), 0.0f);
}

// Perspective camera at the origin looking down -z, 90° vertical fov, square viewport.
mat4 test_view_proj() { return glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, 0.1f, 100.0f); }

std::vector<int> count_coverage(const Soup& soup, int w, int h, CullMode cull = CullMode::None,
                                const mat4& view_proj = mat4(1.0f)) {
  std::vector<int> counts(size_t(w) * h, 0);
  CountingShader shader{w, &counts};
  DepthTarget depth;
  rasterize(soup.views(), view_proj, cull, w, h, depth, shader);
  return counts;
}

// A mesh's box is outside the frustum when all 8 corners are beyond one clip plane: with the
// identity as view-projection (clip = world, w = 1), a unit box moved past each of x = ±1,
// y = ±1 and z = −1 (the near plane) is outside; one that reaches into the cube from any side,
// or lies beyond two planes only in part, is not.
TEST(Raster, BoxOutsideFrustumOnEachPlane) {
  const mat4 id(1.0f);
  const vec3 half(0.25f);
  for (const vec3& c : {vec3(1.5f, 0, 0), vec3(-1.5f, 0, 0), vec3(0, 1.5f, 0), vec3(0, -1.5f, 0),
                        vec3(0, 0, -1.5f)})
    EXPECT_TRUE(box_outside_frustum(c - half, c + half, id)) << c.x << " " << c.y << " " << c.z;
  for (const vec3& c : {vec3(1.1f, 0, 0), vec3(-1.1f, 0, 0), vec3(0, 1.1f, 0), vec3(0, -1.1f, 0),
                        vec3(0, 0, -1.1f), vec3(0, 0, 0), vec3(0, 0, 1.5f), vec3(1.1f, 1.1f, 0)})
    EXPECT_FALSE(box_outside_frustum(c - half, c + half, id)) << c.x << " " << c.y << " " << c.z;
}

TEST(Raster, FanCoversEveryPixelExactlyOnce) {
  // A fan around an interior point whose rim runs along the viewport border: the union is the
  // whole viewport, so every pixel centre must be covered exactly once.
  const int w = 97, h = 61;
  Soup soup;
  soup.positions.push_back(ndc(40.5, 30.5, w, h));  // centre exactly on a pixel centre
  std::vector<vec2> rim;
  for (int i = 0; i <= 12; ++i) rim.push_back({w * i / 12.0, 0.0});
  for (int i = 1; i <= 8; ++i) rim.push_back({double(w), h * i / 8.0});
  for (int i = 11; i >= 0; --i) rim.push_back({w * i / 12.0, double(h)});
  for (int i = 7; i >= 1; --i) rim.push_back({0.0, h * i / 8.0});
  for (const vec2& p : rim) soup.positions.push_back(ndc(p.x, p.y, w, h));
  const uint32_t n = uint32_t(rim.size());
  for (uint32_t i = 0; i < n; ++i) {
    soup.indices.push_back(0);
    soup.indices.push_back(1 + i);
    soup.indices.push_back(1 + (i + 1) % n);
  }
  const std::vector<int> counts = count_coverage(soup, w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ASSERT_EQ(counts[size_t(y) * w + x], 1) << "pixel " << x << "," << y;
}

TEST(Raster, RandomTriangulationIsWatertight) {
  // A jittered grid (interior vertices moved by up to a quarter cell, so every cell stays convex; random, some snapped onto pixel centres and tile
  // boundaries), each cell split into two triangles with a random diagonal and random winding.
  for (uint32_t seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.25, 0.25);
    const int w = 150, h = 131, gx = 9, gy = 7;
    Soup soup;
    for (int j = 0; j <= gy; ++j)
      for (int i = 0; i <= gx; ++i) {
        double sx = double(w) * i / gx, sy = double(h) * j / gy;
        if (i > 0 && i < gx) sx += jitter(rng) * w / gx;
        if (j > 0 && j < gy) sy += jitter(rng) * h / gy;
        if ((i + j) % 3 == 0 && i > 0 && i < gx && j > 0 && j < gy) {
          sx = std::floor(sx) + 0.5;  // on a pixel centre
          sy = std::floor(sy) + 0.5;
        }
        soup.positions.push_back(ndc(sx, sy, w, h));
      }
    auto id = [&](int i, int j) { return uint32_t(j * (gx + 1) + i); };
    for (int j = 0; j < gy; ++j)
      for (int i = 0; i < gx; ++i) {
        uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
        uint32_t t[2][3];
        if (rng() & 1) {
          t[0][0] = a; t[0][1] = b; t[0][2] = c; t[1][0] = a; t[1][1] = c; t[1][2] = d;
        } else {
          t[0][0] = a; t[0][1] = b; t[0][2] = d; t[1][0] = b; t[1][1] = c; t[1][2] = d;
        }
        for (auto& tri : t) {
          if (rng() & 1) std::swap(tri[1], tri[2]);
          soup.indices.insert(soup.indices.end(), tri, tri + 3);
        }
      }
    const std::vector<int> counts = count_coverage(soup, w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_EQ(counts[size_t(y) * w + x], 1) << "seed " << seed << " pixel " << x << "," << y;
  }
}

TEST(Raster, TriangleFarLargerThanViewportCoversAll) {
  // Vertices ~1e4 viewport widths away: clipped to the guard band, still covers every pixel.
  const int w = 33, h = 17;
  Soup soup;
  soup.positions = {{-3e4f, -3e4f, 0.0f}, {3e4f, -3e4f, 0.0f}, {0.0f, 3e4f, 0.0f}};
  soup.indices = {0, 1, 2};
  const std::vector<int> counts = count_coverage(soup, w, h);
  for (int c : counts) ASSERT_EQ(c, 1);
}

TEST(Raster, BackFaceCullingFollowsNdcWinding) {
  const int w = 16, h = 16;
  Soup soup;  // counter-clockwise in NDC: front-facing
  soup.positions = {{-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}};
  soup.indices = {0, 1, 2};
  auto sum = [](const std::vector<int>& v) { int s = 0; for (int c : v) s += c; return s; };
  EXPECT_EQ(sum(count_coverage(soup, w, h, CullMode::Back)), w * h);
  EXPECT_EQ(sum(count_coverage(soup, w, h, CullMode::Front)), 0);
}

TEST(Raster, DegenerateAndNonFiniteTrianglesProduceNothing) {
  const int w = 16, h = 16;
  Soup soup;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  soup.positions = {{-0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {0.0f, 0.0f, 0},   // collinear
                    {-0.5f, -0.5f, 0}, {-0.5f, -0.5f, 0}, {-0.5f, -0.5f, 0}, // a point
                    {nan, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0},
                    {inf, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}};
  for (uint32_t i = 0; i < 12; ++i) soup.indices.push_back(i);
  std::vector<int> counts(size_t(w) * h, 0);
  CountingShader shader{w, &counts};
  DepthTarget depth;
  const RasterStats st = rasterize(soup.views(), mat4(1.0f), CullMode::None, w, h, depth, shader);
  for (int c : counts) EXPECT_EQ(c, 0);
  EXPECT_EQ(st.dropped_nonfinite, 2u);
  EXPECT_EQ(st.dropped_degenerate, 2u);
}

TEST(Raster, NearPlaneClippingAndBehindTheEye) {
  const int w = 32, h = 32;
  // A big floor-like triangle from behind the eye to far in front: crosses the near plane.
  Soup crossing;
  crossing.positions = {{-50, -1, 5}, {50, -1, 5}, {0, -1, -50}};
  crossing.indices = {0, 1, 2};
  std::vector<int> counts = count_coverage(crossing, w, h, CullMode::None, test_view_proj());
  // y = -1 plane seen from the origin: visible below the horizon (lower half of the image).
  int lower = 0, upper = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) (y >= h / 2 ? lower : upper) += counts[size_t(y) * w + x];
  EXPECT_GT(lower, w * h / 4);
  EXPECT_EQ(upper, 0);
  // Entirely behind the eye: nothing.
  Soup behind;
  behind.positions = {{-1, -1, 1}, {1, -1, 1}, {0, 1, 2}};
  behind.indices = {0, 1, 2};
  Soup* s = &behind;
  std::vector<int> none(size_t(w) * h, 0);
  CountingShader shader{w, &none};
  DepthTarget depth;
  const RasterStats st = rasterize(s->views(), test_view_proj(), CullMode::None, w, h, depth, shader);
  for (int c : none) EXPECT_EQ(c, 0);
  EXPECT_EQ(st.culled_frustum, 1u);
  (void)counts;
}

TEST(Raster, DepthIsReciprocalViewDepth) {
  // A plane at z = -4 facing the camera: every pixel's 1/w must be 1/4.
  const int w = 8, h = 8;
  Soup soup;
  soup.positions = {{-100, -100, -4}, {100, -100, -4}, {0, 100, -4}};
  soup.indices = {0, 1, 2};
  DepthTarget depth;
  DepthOnlyShader shader;
  rasterize(soup.views(), test_view_proj(), CullMode::None, w, h, depth, shader);
  for (float iw : depth.inv_w) EXPECT_NEAR(iw, 0.25f, 1e-6f);
}

TEST(Raster, NonMultipleOfTileAndOnePixelViewports) {
  for (int size : {1, 63, 65, 129}) {
    Soup soup;
    soup.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    soup.indices = {0, 1, 2, 0, 2, 3};
    const std::vector<int> counts = count_coverage(soup, size, size + 3);
    for (int c : counts) ASSERT_EQ(c, 1) << "size " << size;
  }
}

// A viewport without pixels (zero width or height) draws nothing, whatever the triangles.
TEST(Raster, EmptyViewportsDrawNothing) {
  Soup soup;
  soup.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  soup.indices = {0, 1, 2, 0, 2, 3};
  for (const auto& [w, h] : {std::pair{64, 0}, std::pair{0, 64}, std::pair{0, 0}}) {
    const std::vector<int> counts = count_coverage(soup, w, h);
    EXPECT_TRUE(counts.empty()) << w << "x" << h;
  }
}

// Tile coordinates are binned in 16 bits: 65,536 tiles of 64 pixels (2^22 pixels) a side are
// the most a viewport may have; one pixel more is refused, in either direction.
TEST(Raster, ViewportsBeyondTheTileIndexRangeAreRefused) {
  const int most = 65536 * kTileSize;
  EXPECT_NO_THROW(bin_triangles({}, mat4(1.0f), CullMode::None, most, 1));
  EXPECT_NO_THROW(bin_triangles({}, mat4(1.0f), CullMode::None, 1, most));
  EXPECT_THROW(bin_triangles({}, mat4(1.0f), CullMode::None, most + 1, 1), std::invalid_argument);
  EXPECT_THROW(bin_triangles({}, mat4(1.0f), CullMode::None, 1, most + 1), std::invalid_argument);
}

// Random triangles in front of the camera; the depth buffer must not depend on threads.
TEST(Raster, DepthIdenticalForAnyThreadCount) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  Soup soup;
  for (int i = 0; i < 3 * 20000; ++i) soup.positions.push_back({u(rng), u(rng), u(rng) - 4.5f});
  for (uint32_t i = 0; i < soup.positions.size(); ++i) soup.indices.push_back(i);
  std::vector<LineAlignedFloats> results;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    DepthTarget depth;
    DepthOnlyShader shader;
    rasterize(soup.views(), test_view_proj(), CullMode::None, 300, 211, depth, shader);
    results.push_back(depth.inv_w);
  }
  set_thread_count(2);
  for (size_t i = 1; i < results.size(); ++i)
    EXPECT_EQ(0, std::memcmp(results[0].data(), results[i].data(), results[0].size() * 4));
}

TEST(Raster, AddStatsSumsEveryCount) {
  // Each field a different power of two: a field left out, assigned or taken from the wrong
  // side shows in the sums.
  RasterStats a{1, 2, 4, 8, 16, 32, 64, 128};
  const RasterStats b{256, 512, 1024, 2048, 4096, 8192, 16384, 32768};
  add_stats(a, b);
  EXPECT_EQ(a.triangles_in, 257u);
  EXPECT_EQ(a.culled_frustum, 514u);
  EXPECT_EQ(a.culled_facing, 1028u);
  EXPECT_EQ(a.dropped_degenerate, 2056u);
  EXPECT_EQ(a.dropped_nonfinite, 4112u);
  EXPECT_EQ(a.clipped, 8224u);
  EXPECT_EQ(a.setups, 16448u);
  EXPECT_EQ(a.fragments, 32896u);
}

}  // namespace
}  // namespace shadowlab
