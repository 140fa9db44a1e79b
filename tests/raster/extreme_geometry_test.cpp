// Extreme geometry through the whole rasterizer (transform, clipping, setup, binning, tiles),
// each case with an expected result from analysis or from an independent ray cast in double
// precision: triangles crossing the near plane or behind the eye, triangles far larger than
// the viewport (guard band) with their depth checked against the analytic plane depth, and
// geometry 1e5 m from the origin seen from a camera nearby.
//
// Depth criterion: the 1e-4 relative, at every covered pixel. A rasterizer that
// interpolates 1/w over the SNAPPED triangle (vertices moved by up to 2^-9 pixel) is off by up
// to (|∂(1/w)/∂x| + |∂(1/w)/∂y|)·2^-9, which is far more where 1/w is small next to its screen
// gradient: 1.5e-3 at the horizon rows of the floors below and 3.6e-2 on nearly edge-on
// triangles (measured on the setup of commit 34c79c7). Planes computed from the unsnapped
// screen positions stay below ~2e-5 on all of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "core/scene.h"
#include "raster/pipeline.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Per pixel: how many fragments were shaded and the 1/w of the last one. Discards, so every
// covered pixel centre of every triangle is seen (no depth test hides any).
struct ProbeShader {
  static constexpr bool kNeedsAttributes = false;
  int width;
  std::vector<int>* count;
  std::vector<float>* inv_w;
  bool operator()(const Fragment& f) {
    const size_t i = size_t(f.y) * size_t(width) + size_t(f.x);
    ++(*count)[i];
    (*inv_w)[i] = f.inv_w;
    return false;
  }
};

struct Probe {
  std::vector<int> count;
  std::vector<float> inv_w;
  RasterStats stats;
};

// Rasterizes world-space triangles (3 vertices each) with the camera's view and projection, as
// the camera pass does.
Probe render(const std::vector<vec3>& triangles, const Camera& cam) {
  std::vector<uint32_t> idx(triangles.size());
  for (uint32_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const std::vector<MeshView> views{
      {triangles.data(), triangles.size(), idx.data(), idx.size() / 3}};
  Probe p;
  p.count.assign(size_t(cam.width) * cam.height, 0);
  p.inv_w.assign(size_t(cam.width) * cam.height, 0.0f);
  ProbeShader shader{cam.width, &p.count, &p.inv_w};
  DepthTarget depth;
  p.stats = rasterize(views, camera_projection(cam) * camera_view(cam), CullMode::None, cam.width,
                      cam.height, depth, shader);
  return p;
}

// The independent expectation: a ray cast in double from the camera's exact parameters (not its
// float matrices) through image point (px, py) (pixels, y down), intersected with the triangle.
// Returns the view depth of the hit when it lies at or beyond the near plane (the only depth
// clip of the rasterizer).
struct RayCamera {
  dvec3 eye, forward, right, up;
  double tan_y, aspect, near;
  int width, height;
  explicit RayCamera(const Camera& c)
      : eye(c.eye),
        tan_y(std::tan(double(c.fov_y_deg) * M_PI / 360.0)),
        aspect(double(c.width) / double(c.height)),
        near(c.near),
        width(c.width),
        height(c.height) {
    forward = glm::normalize(dvec3(c.target) - eye);
    right = glm::normalize(glm::cross(forward, dvec3(c.up)));
    up = glm::cross(right, forward);
  }
  // Direction with unit forward component: the hit's ray parameter is its view depth.
  dvec3 direction(double px, double py) const {
    const double nx = 2.0 * px / width - 1.0, ny = 1.0 - 2.0 * py / height;
    return forward + right * (nx * tan_y * aspect) + up * (ny * tan_y);
  }
  std::optional<double> hit(const dvec3& a, const dvec3& b, const dvec3& c, double px,
                            double py) const {
    const dvec3 d = direction(px, py);
    const dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return std::nullopt;
    const dvec3 s = eye - a;
    const double u = glm::dot(s, p) / det;
    const dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) return std::nullopt;
    const double t = glm::dot(e2, q) / det;
    if (t < near) return std::nullopt;
    return t;
  }
};

// Worst relative error of the view depth 1/inv_w over a set of pixels.
struct DepthStats {
  double worst_rel = 0.0;
  size_t pixels = 0;
  void add(double iw_raster, double depth) {
    ++pixels;
    worst_rel = test::worst_of(worst_rel, std::fabs(1.0 / iw_raster - depth) / depth);
  }
};

Camera looking_down_minus_z(int w, int h, float near = 0.1f) {
  Camera c;
  c.eye = vec3(0.0f);
  c.target = vec3(0.0f, 0.0f, -1.0f);
  c.up = vec3(0.0f, 1.0f, 0.0f);
  c.fov_y_deg = 90.0f;
  c.near = near;
  c.far = 1000.0f;
  c.width = w;
  c.height = h;
  return c;
}

TEST(ExtremeGeometry, NearPlaneCutsAFloorThroughTheEye) {
  // The plane y = −0.05 (a floor just below the eye), as one triangle reaching from behind the
  // eye (z = +5) to z = −50, seen with a 90° fov, near 0.1, 64 × 64. The ray through row y has
  // slope s = (y + 0.5 − 32)/32 below the horizon and meets the floor at depth 0.05/s:
  //  - rows 0..31 look above the horizon: empty;
  //  - rows 32..47 (s <= 0.484) meet it at depth >= 0.103: covered across the whole width (the
  //    triangle is ≥ 42 m wide there);
  //  - rows 48..63 (s >= 0.516) would meet it at depth <= 0.097, in front of the near plane:
  //    cut away. The cut lies at screen y = 48 exactly, half a pixel from the centres.
  // Depth: 1/inv_w = 0.05/s.
  const Camera cam = looking_down_minus_z(64, 64);
  const Probe p = render({{-50, -0.05f, 5}, {50, -0.05f, 5}, {0, -0.05f, -50}}, cam);
  EXPECT_EQ(p.stats.clipped, 1u);
  DepthStats d;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t i = size_t(y) * 64 + size_t(x);
      ASSERT_EQ(p.count[i], (y >= 32 && y < 48) ? 1 : 0) << "pixel " << x << "," << y;
      if (!p.count[i]) continue;
      const double s = (y + 0.5 - 32.0) / 32.0;
      d.add(p.inv_w[i], 0.05 / s);
    }
  EXPECT_EQ(d.pixels, 64u * 16u);
  EXPECT_LE(d.worst_rel, 1e-4) << "largest relative depth error";
}

TEST(ExtremeGeometry, TrianglesBehindTheEyeDrawNothing) {
  const Camera cam = looking_down_minus_z(48, 32);
  // Entirely behind the eye (z > 0). A naive projection (divide by a negative w) would flip the
  // first one onto the screen, covering much of it.
  const std::vector<vec3> behind = {{-10, -10, 1},
                                    {10, -10, 1},
                                    {0, 10, 1},
                                    {-1, -1, 0.5f},
                                    {1, -1, 3},
                                    {0, 1, 0.01f},
                                    // in the eye plane z = 0 (w = 0 at every vertex)
                                    {-1, -1, 0},
                                    {1, -1, 0},
                                    {0, 1, 0},
                                    // in front of the eye but nearer than the near plane
                                    {-0.01f, -0.01f, -0.05f},
                                    {0.01f, -0.01f, -0.05f},
                                    {0, 0.01f, -0.09f}};
  const Probe p = render(behind, cam);
  for (int c : p.count) ASSERT_EQ(c, 0);
  EXPECT_EQ(p.stats.triangles_in, 4u);
  EXPECT_EQ(p.stats.culled_frustum, 4u);  // all three vertices beyond the near plane
}

TEST(ExtremeGeometry, TrianglesCrossingTheNearPlaneMatchARayCast) {
  // Random triangles in a box around the eye, many with one or two vertices behind it: the
  // covered pixels must be exactly those whose centre ray hits the triangle at depth >= near,
  // and the depth must be the hit's. A pixel whose answer changes within ±0.01 pixel or whose
  // hit lies within 1e-5 m of the near plane is ambiguous under float input and is skipped (few).
  const Camera cam = looking_down_minus_z(80, 60, 0.1f);
  const RayCamera rc(cam);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> xy(-3.0f, 3.0f), z(-5.0f, 2.0f);
  size_t checked = 0, skipped = 0, covered = 0, crossing = 0;
  DepthStats d;
  for (int t = 0; t < 60; ++t) {
    const std::vector<vec3> tri = {
        {xy(rng), xy(rng), z(rng)}, {xy(rng), xy(rng), z(rng)}, {xy(rng), xy(rng), z(rng)}};
    int behind = 0;
    for (const vec3& v : tri) behind += v.z > -cam.near;
    crossing += behind == 1 || behind == 2;
    const Probe p = render(tri, cam);
    const dvec3 a(tri[0]), b(tri[1]), c(tri[2]);
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const size_t i = size_t(y) * cam.width + size_t(x);
        const std::optional<double> h = rc.hit(a, b, c, x + 0.5, y + 0.5);
        bool ambiguous = h && std::fabs(*h - rc.near) < 1e-5;
        for (const auto& o : {std::pair{0.01, 0.0}, {-0.01, 0.0}, {0.0, 0.01}, {0.0, -0.01}})
          ambiguous =
              ambiguous ||
              rc.hit(a, b, c, x + 0.5 + o.first, y + 0.5 + o.second).has_value() != h.has_value();
        ASSERT_LE(p.count[i], 1) << "triangle " << t << " pixel " << x << "," << y;
        if (ambiguous) {
          ++skipped;
          continue;
        }
        ++checked;
        ASSERT_EQ(p.count[i], h ? 1 : 0) << "triangle " << t << " pixel " << x << "," << y;
        if (!h || p.count[i] != 1) continue;
        ++covered;
        d.add(p.inv_w[i], *h);
      }
  }
  EXPECT_GE(crossing, 20u) << "the sample must exercise near-plane clipping";
  EXPECT_GT(covered, checked / 20);
  EXPECT_LE(skipped, checked / 100);
  EXPECT_LE(d.worst_rel, 1e-4) << "largest relative depth error";
}

TEST(ExtremeGeometry, GuardBandFloorAndWallHaveExactCoverageAndDepth) {
  // Camera at the origin looking down −z, 90° fov, 64 × 64 (1 NDC unit = 32 pixels; the guard
  // band is 16384 pixels = 512 NDC units). Floor y = −1 as the triangle (−1000, −1, −1),
  // (1000, −1, −1), (0, −1, −1000): its near vertices project to x = ±1000 NDC, far outside the
  // guard band, so it is clipped against it (but not against the near plane). Row y's centre
  // ray has slope s = (y + 0.5 − 32)/32 and meets the floor at depth 1/s, within the triangle
  // for every column (≥ 936 m wide there, depth ≥ 1.016): rows 32..63 covered once, rows 0..31
  // empty, 1/inv_w = 1/s. The wall x = −1, rotated the same way, covers columns 0..31 with
  // depth 1/s', s' = (32 − x − 0.5)/32.
  const Camera cam = looking_down_minus_z(64, 64, 0.05f);
  DepthStats d;
  for (int wall = 0; wall < 2; ++wall) {
    const std::vector<vec3> tri =
        wall == 0 ? std::vector<vec3>{{-1000, -1, -1}, {1000, -1, -1}, {0, -1, -1000}}
                  : std::vector<vec3>{{-1, -1000, -1}, {-1, 1000, -1}, {-1, 0, -1000}};
    const Probe p = render(tri, cam);
    EXPECT_EQ(p.stats.clipped, 1u) << "wall " << wall;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const size_t i = size_t(y) * 64 + size_t(x);
        const bool in = wall == 0 ? y >= 32 : x < 32;
        ASSERT_EQ(p.count[i], in ? 1 : 0) << "wall " << wall << " pixel " << x << "," << y;
        if (!in || p.count[i] != 1) continue;
        const double s = wall == 0 ? (y + 0.5 - 32.0) / 32.0 : (32.0 - x - 0.5) / 32.0;
        d.add(p.inv_w[i], 1.0 / s);
      }
  }
  EXPECT_EQ(d.pixels, 2u * 64u * 32u);
  EXPECT_LE(d.worst_rel, 1e-4) << "largest relative depth error";
}

TEST(ExtremeGeometry, HugeTiltedTriangleCoversEverythingWithPlaneDepth) {
  // The plane through (0, 0, −10) with normal (0.3, 0.4, 1), as one triangle with vertices 1e4 m
  // away in it (beyond the guard band in every direction, two of them behind the eye: clipped
  // by both). Every centre ray (u·a, v, −1) (90° fov, aspect a = 96/64) meets it at depth
  // t = 10 / (1 − 0.3·u·a − 0.4·v) > 0, so every pixel is covered once, with 1/inv_w = t.
  Camera cam = looking_down_minus_z(96, 64, 0.05f);
  const dvec3 n = glm::normalize(dvec3(0.3, 0.4, 1.0));
  const dvec3 p0(0.0, 0.0, -10.0);
  const dvec3 t1 = glm::normalize(glm::cross(n, dvec3(0, 1, 0))), t2 = glm::cross(n, t1);
  std::vector<vec3> tri;
  for (int k = 0; k < 3; ++k) {
    const double ang = 2.0 * M_PI * k / 3.0 + 0.3;
    tri.push_back(vec3(p0 + 1e4 * (std::cos(ang) * t1 + std::sin(ang) * t2)));
  }
  const Probe p = render(tri, cam);
  EXPECT_EQ(p.stats.clipped, 1u);
  // The float vertices are off the exact plane by ~1e4·6e-8 m: use the plane through them.
  const dvec3 a0(tri[0]), a1(tri[1]), a2(tri[2]);
  const dvec3 nn = glm::cross(a1 - a0, a2 - a0);
  const RayCamera rc(cam);
  auto inv_depth = [&](double px, double py) {
    return glm::dot(nn, rc.direction(px, py)) / glm::dot(nn, a0);
  };
  DepthStats d;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x) {
      const size_t i = size_t(y) * 96 + size_t(x);
      ASSERT_EQ(p.count[i], 1) << "pixel " << x << "," << y;
      if (p.count[i] != 1) continue;
      d.add(p.inv_w[i], 1.0 / inv_depth(x + 0.5, y + 0.5));
    }
  EXPECT_EQ(d.pixels, 96u * 64u);
  EXPECT_LE(d.worst_rel, 1e-4) << "largest relative depth error";
}

TEST(ExtremeGeometry, QuadFarFromTheOriginAxisAligned) {
  // A 2 × 2 m quad in the plane x = 1e5 (y, z in [−1, 1]) seen from (1e5 − 3, 0, 0) looking +x,
  // 90° fov, 96 × 96. Every coordinate, and the view matrix (axes ±1, translation 99997), is
  // exact in float. Image x = world z: the quad spans NDC ±1/3 = pixels [32, 64) in x and y,
  // edges on pixel boundaries half a pixel from the centres; depth 3 m everywhere.
  Camera cam;
  cam.eye = vec3(1e5f - 3.0f, 0.0f, 0.0f);
  cam.target = vec3(1e5f, 0.0f, 0.0f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.fov_y_deg = 90.0f;
  cam.near = 0.05f;
  cam.far = 100.0f;
  cam.width = cam.height = 96;
  const float X = 1e5f;
  const Probe p =
      render({{X, -1, -1}, {X, -1, 1}, {X, 1, 1}, {X, -1, -1}, {X, 1, 1}, {X, 1, -1}}, cam);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const size_t i = size_t(y) * 96 + size_t(x);
      const bool in = x >= 32 && x < 64 && y >= 32 && y < 64;
      ASSERT_EQ(p.count[i], in ? 1 : 0) << "pixel " << x << "," << y;
      if (in) {
        ASSERT_NEAR(1.0 / p.inv_w[i], 3.0, 3.0 * 1e-6) << "pixel " << x << "," << y;
      }
    }
}

TEST(ExtremeGeometry, QuadFarFromTheOriginTiltedCamera) {
  // The same quad seen from a tilted camera near it: eye (1e5 − 3, 0.25, −0.35), target
  // (1e5, 0.1, 0.2). Now the float view-projection matrix carries translations of ~1e5 rounded
  // to their float spacing (2^-7 m), so the clip coordinates are off by up to ~1e-2 m: at 3 m
  // that is < 0.2 pixel and < 0.5 % of the depth. Expected (from the double ray cast of the
  // exact camera): the covered set differs only on pixels next to the rectangle's true edge
  // (a pixel that differs has a neighbour where the ray cast agrees with the rasterizer), and
  // the depth matches the ray cast within 0.5 %.
  Camera cam;
  cam.eye = vec3(1e5f - 3.0f, 0.25f, -0.35f);
  cam.target = vec3(1e5f, 0.1f, 0.2f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.fov_y_deg = 90.0f;
  cam.near = 0.05f;
  cam.far = 100.0f;
  cam.width = cam.height = 96;
  const float X = 1e5f;
  const std::vector<vec3> quad = {{X, -1, -1}, {X, -1, 1}, {X, 1, 1},
                                  {X, -1, -1}, {X, 1, 1},  {X, 1, -1}};
  const Probe p = render(quad, cam);
  const RayCamera rc(cam);
  auto expected = [&](int x, int y) -> std::optional<double> {
    if (x < 0 || y < 0 || x >= 96 || y >= 96) return std::nullopt;
    for (int t = 0; t < 2; ++t) {
      const auto h = rc.hit(dvec3(quad[3 * t]), dvec3(quad[3 * t + 1]), dvec3(quad[3 * t + 2]),
                            x + 0.5, y + 0.5);
      if (h) return h;
    }
    return std::nullopt;
  };
  size_t covered = 0, edge_mismatch = 0;
  double worst = 0.0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const size_t i = size_t(y) * 96 + size_t(x);
      ASSERT_LE(p.count[i], 1);
      const std::optional<double> h = expected(x, y);
      if (p.count[i] == (h ? 1 : 0)) {
        if (h) {
          ++covered;
          worst = test::worst_of(worst, std::fabs(1.0 / p.inv_w[i] - *h) / *h);
        }
        continue;
      }
      ++edge_mismatch;
      bool next_to_edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          next_to_edge = next_to_edge || expected(x + dx, y + dy).has_value() == (p.count[i] == 1);
      EXPECT_TRUE(next_to_edge) << "pixel " << x << "," << y << " is more than a pixel off";
    }
  EXPECT_GT(covered, 500u);
  EXPECT_LE(edge_mismatch, 20u);
  EXPECT_LE(worst, 5e-3) << "largest relative depth error";
}

}  // namespace
}  // namespace shadowlab
