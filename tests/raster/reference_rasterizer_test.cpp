// rasterize() against a brute-force reference rasterizer written here: every pixel centre of
// the viewport is tested against every triangle with exact 64-bit integer edge functions on the
// fixed-point vertices and the top-left rule as raster/setup.h documents it. Covered sets must
// be identical — on random perspective triangle soups, on tile and pixel-centre boundaries, on
// 1×1 and non-multiple-of-tile viewports, for slivers and zero-area triangles, and with NaN/Inf
// vertices mixed in.
//
// How the inputs stay exact: every vertex is built in view space as (ndc_x·w, ndc_y·w, −w)
// with w a power of two and ndc a multiple of 2^-15, under a hand-made 90° projection whose x/y
// rows are the identity (projection()). Clip x, y and w are then exact in float, and the screen
// position in subpixels, (ndc + 1)·W·128, is a multiple of 1/256 subpixel that is kept at least
// 4/256 away from a rounding tie, so any exact or float viewport transform followed by
// round-to-nearest snaps it to the same integer — the one the reference computes in integers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "raster/pipeline.h"

namespace shadowlab {
namespace {

constexpr int kNdcBits = 15;  // NDC coordinates are multiples of 2^-15
constexpr int64_t kNdcOne = int64_t(1) << kNdcBits;

// 90° perspective (x and y rows identity), near 0.25, far 64: clip = (x, y, ·, −z).
mat4 projection() {
  const float n = 0.25f, f = 64.0f;
  mat4 p(0.0f);
  p[0][0] = 1.0f;
  p[1][1] = 1.0f;
  p[2][2] = -(f + n) / (f - n);
  p[3][2] = -2.0f * f * n / (f - n);
  p[2][3] = -1.0f;
  return p;
}

// One vertex: its view-space (= world) position, its NDC numerators (ndc = n / 2^15) and the
// fixed-point screen position that the reference uses (subpixels, 8 fractional bits, y down).
struct ExactVertex {
  vec3 position;
  int64_t nx = 0, ny = 0;
  int64_t fx = 0, fy = 0;
};

// Rounds num / 256 to the nearest integer; num mod 256 must not be within 4 of a tie (128).
int64_t round_div256(int64_t num) {
  const int64_t q = num >= 0 ? num / 256 : -((-num + 255) / 256);  // floor
  const int64_t r = num - q * 256;                                 // in [0, 256)
  return r < 128 ? q : q + 1;
}
bool near_tie(int64_t num) {
  const int64_t r = ((num % 256) + 256) % 256;
  return r >= 124 && r <= 132;
}

// Screen x in subpixels is (ndc_x + 1)/2 · W · 256 = (nx + 2^15) · W / 256 for ndc_x = nx/2^15;
// y is flipped: (1 − ndc_y)/2 · H · 256 = (2^15 − ny) · H / 256.
ExactVertex vertex_from_ndc(int64_t nx, int64_t ny, float w, int width, int height) {
  ExactVertex v;
  v.nx = nx;
  v.ny = ny;
  v.fx = round_div256((nx + kNdcOne) * width);
  v.fy = round_div256((kNdcOne - ny) * height);
  const float ndc_x = float(nx) / float(kNdcOne), ndc_y = float(ny) / float(kNdcOne);
  v.position = vec3(ndc_x * w, ndc_y * w, -w);  // exact: w is a power of two
  return v;
}
int64_t ndc_x_for(double tx, int width) {
  int64_t nx = std::llround(tx * 256.0 / width) - kNdcOne;
  while (near_tie((nx + kNdcOne) * width)) ++nx;
  return nx;
}
int64_t ndc_y_for(double ty, int height) {
  int64_t ny = kNdcOne - std::llround(ty * 256.0 / height);
  while (near_tie((kNdcOne - ny) * height)) ++ny;
  return ny;
}

// The exact vertex at view depth w (a power of two) whose snapped screen position is as close
// as the NDC grid allows to the target (tx, ty), in subpixels.
ExactVertex make_vertex(double tx, double ty, float w, int width, int height) {
  return vertex_from_ndc(ndc_x_for(tx, width), ndc_y_for(ty, height), w, width, height);
}

struct RefTriangle {
  int64_t x[3], y[3];
};

// Brute-force coverage of one triangle: pixel (px, py) is covered iff its centre
// (256·px + 128, 256·py + 128) lies strictly inside every edge, or exactly on an edge that is
// a "top" edge (horizontal, interior below it: y grows downwards) or a "left" edge (interior to
// its right). Zero-area triangles cover nothing. Both windings are drawn.
bool ref_covers(const RefTriangle& t, int64_t cx, int64_t cy) {
  const int64_t area2 =
      (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
  if (area2 == 0) return false;
  const int64_t sign = area2 > 0 ? 1 : -1;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int64_t ex = t.x[j] - t.x[i], ey = t.y[j] - t.y[i];
    // Inward normal (nx, ny) = sign · (−ey, ex): positive towards vertex k.
    const int64_t nx = -ey * sign, ny = ex * sign;
    const int64_t e = nx * (cx - t.x[i]) + ny * (cy - t.y[i]);
    if (e > 0) continue;
    if (e < 0) return false;
    const bool left = nx > 0;
    const bool top = nx == 0 && ny > 0;
    if (!(left || top)) return false;
  }
  return true;
}

uint64_t triangle_hash(uint32_t t) {
  uint64_t h = uint64_t(t) * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return h;
}

// Per pixel: how many triangles cover it and an order-independent hash of which ones.
struct CoverageSets {
  int width = 0, height = 0;
  std::vector<uint32_t> count;
  std::vector<uint64_t> hash;
  CoverageSets(int w, int h)
      : width(w), height(h), count(size_t(w) * h, 0), hash(size_t(w) * h, 0) {}
};

// Records every covered pixel and discards, so the depth test never hides a fragment.
template <bool kAttributes>
struct RecordingShader {
  static constexpr bool kNeedsAttributes = kAttributes;
  CoverageSets* sets;
  bool operator()(const Fragment& f) {
    const size_t i = size_t(f.y) * size_t(sets->width) + size_t(f.x);
    ++sets->count[i];
    sets->hash[i] += triangle_hash(f.triangle);
    return false;
  }
};

// A soup: several meshes (the global triangle index runs over them) of exact vertices.
struct ExactSoup {
  std::vector<std::vector<ExactVertex>> vertices;  // per mesh
  std::vector<std::vector<uint32_t>> indices;      // per mesh
  std::vector<std::vector<vec3>> positions;        // filled by views()
  std::vector<MeshView> views() {
    positions.assign(vertices.size(), {});
    std::vector<MeshView> v;
    for (size_t m = 0; m < vertices.size(); ++m) {
      for (const ExactVertex& e : vertices[m]) positions[m].push_back(e.position);
      v.push_back(
          {positions[m].data(), positions[m].size(), indices[m].data(), indices[m].size() / 3});
    }
    return v;
  }
  size_t triangle_count() const {
    size_t n = 0;
    for (const auto& i : indices) n += i.size() / 3;
    return n;
  }
};

// Reference coverage of every triangle of the soup whose vertices are all marked good.
CoverageSets reference(const ExactSoup& soup, int width, int height,
                       const std::vector<std::vector<bool>>* bad = nullptr) {
  CoverageSets sets(width, height);
  uint32_t global = 0;
  for (size_t m = 0; m < soup.vertices.size(); ++m)
    for (size_t t = 0; t + 2 < soup.indices[m].size(); t += 3, ++global) {
      RefTriangle tri;
      bool skip = false;
      for (int k = 0; k < 3; ++k) {
        const uint32_t vi = soup.indices[m][t + size_t(k)];
        if (bad && (*bad)[m][vi]) skip = true;
        tri.x[k] = soup.vertices[m][vi].fx;
        tri.y[k] = soup.vertices[m][vi].fy;
      }
      if (skip) continue;
      for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px)
          if (ref_covers(tri, 256 * int64_t(px) + 128, 256 * int64_t(py) + 128)) {
            const size_t i = size_t(py) * size_t(width) + size_t(px);
            ++sets.count[i];
            sets.hash[i] += triangle_hash(global);
          }
    }
  return sets;
}

// Keeps every fragment like DepthOnlyShader but does not declare kKeepsAll, so the rasterizer
// takes its general per-fragment path: the oracle for the depth-only fast path.
struct KeepEverythingShader {
  static constexpr bool kNeedsAttributes = false;
  int calls = 0;  // a side effect, so no path may skip the call
  bool operator()(const Fragment&) {
    ++calls;
    return true;
  }
};

// The depth-only fast path (DepthOnlyShader) must write exactly the bytes of the general path,
// and its covered pixels (1/w > 0) must be the union of the reference's coverage sets.
void expect_fast_path_agrees(ExactSoup& soup, int width, int height, const CoverageSets& expected,
                             const std::string& what) {
  DepthTarget fast, general;
  DepthOnlyShader depth_only;
  KeepEverythingShader keep;
  rasterize(soup.views(), projection(), CullMode::None, width, height, fast, depth_only);
  rasterize(soup.views(), projection(), CullMode::None, width, height, general, keep);
  ASSERT_EQ(fast.inv_w.size(), general.inv_w.size());
  size_t differ = 0, union_differ = 0;
  for (size_t i = 0; i < fast.inv_w.size(); ++i) {
    differ += std::memcmp(&fast.inv_w[i], &general.inv_w[i], sizeof(float)) != 0;
    union_differ += (fast.inv_w[i] > 0.0f) != (expected.count[i] > 0);
  }
  EXPECT_EQ(differ, 0u) << what << ": depth-only fast path vs general path";
  EXPECT_EQ(union_differ, 0u) << what << ": depth-only coverage vs reference";
}

template <bool kAttributes>
CoverageSets rasterized(ExactSoup& soup, int width, int height, RasterStats* stats = nullptr,
                        DepthTarget* depth_out = nullptr, const mat4& view_proj = projection()) {
  CoverageSets sets(width, height);
  RecordingShader<kAttributes> shader{&sets};
  DepthTarget depth;
  const RasterStats st =
      rasterize(soup.views(), view_proj, CullMode::None, width, height, depth, shader);
  if (stats) *stats = st;
  if (depth_out) *depth_out = depth;
  return sets;
}

// Lists the triangles (global index, fixed-point vertices) of the soup covering pixel i in the
// reference, for failure messages.
std::string describe_pixel(const ExactSoup& soup, int width, size_t i) {
  std::ostringstream os;
  const int64_t cx = 256 * int64_t(i % size_t(width)) + 128,
                cy = 256 * int64_t(i / size_t(width)) + 128;
  os << "pixel centre (" << cx << ", " << cy << ") subpixels; reference covers:";
  uint32_t global = 0;
  for (size_t m = 0; m < soup.vertices.size(); ++m)
    for (size_t t = 0; t + 2 < soup.indices[m].size(); t += 3, ++global) {
      RefTriangle tri;
      for (int k = 0; k < 3; ++k) {
        const ExactVertex& v = soup.vertices[m][soup.indices[m][t + size_t(k)]];
        tri.x[k] = v.fx;
        tri.y[k] = v.fy;
      }
      if (!ref_covers(tri, cx, cy)) continue;
      os << " #" << global << " (" << tri.x[0] << "," << tri.y[0] << ")(" << tri.x[1] << ","
         << tri.y[1] << ")(" << tri.x[2] << "," << tri.y[2] << ")";
    }
  return os.str();
}

// Number of pixels whose covering set differs; the first few are reported.
size_t compare(const CoverageSets& expected, const CoverageSets& actual, const ExactSoup& soup,
               const std::string& what) {
  size_t differ = 0;
  for (size_t i = 0; i < expected.count.size(); ++i) {
    if (expected.count[i] == actual.count[i] && expected.hash[i] == actual.hash[i]) continue;
    if (++differ <= 3)
      ADD_FAILURE() << what << ": pixel (" << i % size_t(expected.width) << ", "
                    << i / size_t(expected.width) << ") covered " << actual.count[i]
                    << " times, reference " << expected.count[i] << "; "
                    << describe_pixel(soup, expected.width, i);
  }
  return differ;
}

float random_depth(std::mt19937& rng) {
  static const float kDepths[] = {0.5f, 1.0f, 2.0f, 4.0f, 8.0f};
  return kDepths[rng() % 5];
}

// A random target coordinate in subpixels along an axis of `size` pixels: anywhere (including
// up to a quarter viewport outside), on a pixel centre, on a pixel corner, or on a tile
// boundary (exactly, or half a pixel either side: the centres of the pixels next to it).
double random_coordinate(std::mt19937& rng, int size) {
  std::uniform_real_distribution<double> any(-0.25 * size * 256.0, 1.25 * size * 256.0);
  const int kind = int(rng() % 8);
  const int pixel = int(rng() % uint32_t(size + 2)) - 1;
  switch (kind) {
    case 0:
      return 256.0 * pixel + 128.0;
    case 1:
      return 256.0 * pixel;
    case 2: {
      const int tile = int(rng() % uint32_t(size / kTileSize + 2));
      return 256.0 * kTileSize * tile + 128.0 * (int(rng() % 3) - 1);
    }
    default:
      return any(rng);
  }
}

// A random soup of `triangles` triangles in 1–3 meshes: triangles of every size from a pixel
// to the viewport, some sharing edges (fans), some with horizontal or vertical edges, vertices
// at random depths so every triangle is in perspective.
ExactSoup random_soup(uint32_t seed, int width, int height, int triangles) {
  std::mt19937 rng(seed);
  ExactSoup soup;
  const int meshes = 1 + int(rng() % 3);
  soup.vertices.resize(size_t(meshes));
  soup.indices.resize(size_t(meshes));
  const double scale = 256.0 * std::max(width, height);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int t = 0; t < triangles; ++t) {
    const size_t m = size_t(rng() % uint32_t(meshes));
    auto& verts = soup.vertices[m];
    auto& idx = soup.indices[m];
    // Fan: reuse the last edge of this mesh for a neighbour sharing it exactly.
    if (idx.size() >= 3 && rng() % 3 == 0) {
      const uint32_t a = idx[idx.size() - 1], b = idx[idx.size() - 2];
      const double radius = std::max(100.0, scale * std::pow(2.0, -8.0 * unit(rng)));
      std::uniform_real_distribution<double> off(-radius, radius);
      verts.push_back(make_vertex(verts[a].fx + off(rng), verts[a].fy + off(rng), random_depth(rng),
                                  width, height));
      idx.insert(idx.end(), {a, b, uint32_t(verts.size() - 1)});
      continue;
    }
    const double x0 = random_coordinate(rng, width), y0 = random_coordinate(rng, height);
    // Size log-uniform from ~1/2 pixel to ~1.5 viewports.
    const double radius = 1.5 * scale * std::pow(2.0, -12.0 * unit(rng));
    std::uniform_real_distribution<double> off(-radius, radius);
    const double x1 = x0 + off(rng), y1 = y0 + off(rng), x2 = x0 + off(rng), y2 = y0 + off(rng);
    const int shape = int(rng() % 6);
    // shape 0: edge 0–1 horizontal (top or bottom); shape 1: vertical (left or right).
    const uint32_t base = uint32_t(verts.size());
    const ExactVertex v0 = make_vertex(x0, y0, random_depth(rng), width, height);
    // Equal NDC numerators give exactly equal snapped coordinates: a horizontal/vertical edge.
    const int64_t nx1 = shape == 1 ? v0.nx : ndc_x_for(x1, width);
    const int64_t ny1 = shape == 0 ? v0.ny : ndc_y_for(y1, height);
    verts.push_back(v0);
    verts.push_back(vertex_from_ndc(nx1, ny1, random_depth(rng), width, height));
    verts.push_back(make_vertex(x2, y2, random_depth(rng), width, height));
    idx.insert(idx.end(), {base, base + 1, base + 2});
  }
  return soup;
}

// Checks that every vertex of the soup really is exact: its NDC is a multiple of 2^-15 and its
// position (ndc·w, ndc·w, −w) was representable (the shape 0/1 copies rescale by powers of two).
void expect_exact(const ExactSoup& soup, int width, int height) {
  for (const auto& verts : soup.vertices)
    for (const ExactVertex& v : verts) {
      const double w = -double(v.position.z);
      const double nx = double(v.position.x) / w * double(kNdcOne);
      const double ny = double(v.position.y) / w * double(kNdcOne);
      ASSERT_EQ(nx, double(v.nx));
      ASSERT_EQ(ny, double(v.ny));
      ASSERT_FALSE(near_tie((v.nx + kNdcOne) * width));
      ASSERT_FALSE(near_tie((kNdcOne - v.ny) * height));
    }
}

TEST(ReferenceRasterizer, RandomPerspectiveSoupsHaveIdenticalCoverage) {
  // Viewports: one pixel, single rows/columns, tile multiples and non-multiples.
  const int sizes[][2] = {{1, 1},   {1, 9},    {9, 1},     {64, 64},
                          {63, 65}, {130, 67}, {200, 129}, {256, 192}};
  uint32_t seed = 1;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    for (int rep = 0; rep < 8; ++rep, ++seed) {
      ExactSoup soup = random_soup(seed, w, h, w * h < 100 ? 60 : 400);
      expect_exact(soup, w, h);
      const CoverageSets expected = reference(soup, w, h);
      const std::string what = "seed " + std::to_string(seed) + " viewport " + std::to_string(w) +
                               "x" + std::to_string(h);
      EXPECT_EQ(compare(expected, rasterized<false>(soup, w, h), soup, what + " (depth-only)"), 0u);
      EXPECT_EQ(compare(expected, rasterized<true>(soup, w, h), soup, what + " (attributes)"), 0u);
      expect_fast_path_agrees(soup, w, h, expected, what);
    }
  }
}

// A soup from explicit screen positions (pixels) at varying depths, for hand-made cases.
ExactSoup soup_from_pixels(const std::vector<std::array<double, 2>>& pts,
                      const std::vector<uint32_t>& idx, int width, int height) {
  ExactSoup soup;
  soup.vertices.resize(1);
  soup.indices.push_back(idx);
  for (size_t i = 0; i < pts.size(); ++i) {
    const float w = (i % 3 == 0) ? 1.0f : (i % 3 == 1 ? 2.0f : 4.0f);
    soup.vertices[0].push_back(make_vertex(pts[i][0] * 256.0, pts[i][1] * 256.0, w, width, height));
  }
  return soup;
}

// Pixels covered exactly once form the rectangle [x0, x1) × [y0, y1); every other pixel is
// uncovered.
void expect_rectangle(const CoverageSets& c, int x0, int y0, int x1, int y1,
                      const std::string& what) {
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const bool inside = x >= x0 && x < x1 && y >= y0 && y < y1;
      ASSERT_EQ(c.count[size_t(y) * c.width + x], inside ? 1u : 0u)
          << what << " pixel " << x << "," << y;
    }
}

TEST(ReferenceRasterizer, RectangleWithEdgesThroughPixelCentres) {
  // Corners (10.5, 20.5) and (30.5, 40.5), split along the diagonal, which also runs through
  // pixel centres. Top-left rule: the left (x = 10.5) and top (y = 20.5) edges are in, the right
  // and bottom edges out, and each diagonal centre belongs to exactly one of the two triangles:
  // pixels x in [10, 30), y in [20, 40), each exactly once.
  const int w = 64, h = 64;
  for (int diagonal = 0; diagonal < 2; ++diagonal) {
    ExactSoup soup = soup_from_pixels({{10.5, 20.5}, {30.5, 20.5}, {30.5, 40.5}, {10.5, 40.5}},
                                 diagonal == 0 ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3}
                                               : std::vector<uint32_t>{0, 1, 3, 1, 2, 3},
                                 w, h);
    const CoverageSets expected = reference(soup, w, h);
    expect_rectangle(expected, 10, 20, 30, 40, "reference");
    const CoverageSets actual = rasterized<false>(soup, w, h);
    expect_rectangle(actual, 10, 20, 30, 40, "rasterize");
    EXPECT_EQ(compare(expected, actual, soup, "diagonal " + std::to_string(diagonal)), 0u);
  }
}

TEST(ReferenceRasterizer, QuadsOnTileBoundaries) {
  // A quad exactly covering tile (1, 1) — corners on kTileSize multiples — covers exactly its
  // 64 × 64 pixels; one covering 2 × 1 tiles from x = 0 covers those; both windings.
  const int w = 3 * kTileSize + 5, h = 2 * kTileSize + 7;
  const double t = kTileSize;
  for (int winding = 0; winding < 2; ++winding) {
    const std::vector<uint32_t> idx = winding == 0 ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3}
                                                   : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    ExactSoup one = soup_from_pixels({{t, t}, {2 * t, t}, {2 * t, 2 * t}, {t, 2 * t}}, idx, w, h);
    expect_rectangle(rasterized<false>(one, w, h), kTileSize, kTileSize, 2 * kTileSize,
                     2 * kTileSize, "tile (1,1)");
    ExactSoup two = soup_from_pixels({{0, 0}, {2 * t, 0}, {2 * t, t}, {0, t}}, idx, w, h);
    expect_rectangle(rasterized<true>(two, w, h), 0, 0, 2 * kTileSize, kTileSize,
                     "tiles (0..1, 0)");
  }
}

TEST(ReferenceRasterizer, EdgesAndVerticesOnTileBoundaryPixelCentres) {
  // Vertical edges through the centres of the last column of a tile (x = 63.5) and the first
  // of the next (x = 64.5), horizontal ones through y = 63.5 / 64.5, vertices on those centres
  // and on tile corners: coverage as the exact reference says, pixel for pixel.
  const int w = 2 * kTileSize + 9, h = 2 * kTileSize + 3;
  const double a = kTileSize - 0.5, b = kTileSize + 0.5, c = kTileSize;
  ExactSoup soup = soup_from_pixels(
      {// right triangle with its vertical (left) edge at x = 63.5 and top edge at y = 63.5
       {a, a},
       {a + 20, a},
       {a, a + 30},
       // right triangle with its vertical (right) edge at x = 64.5, bottom edge at y = 64.5
       {b, b},
       {b - 20, b},
       {b, b - 30},
       // a thin triangle along the tile column boundary x = 64 (no centre on it)
       {c, 2.0},
       {c + 0.5, 100.0},
       {c, 120.0},
       // a triangle with every vertex on a tile corner
       {0, 0},
       {2 * c, c},
       {c, 2 * c},
       // a fan centred on the pixel centre (64.5, 64.5)
       {b, b},
       {b + 10, b},
       {b, b + 10},
       {b - 10, b},
       {b, b - 10}},
      {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 12, 14, 15, 12, 15, 16, 12, 16, 13}, w, h);
  const CoverageSets expected = reference(soup, w, h);
  // Analytic spot checks of the reference itself. The centre (63.5, 63.5) is the first
  // triangle's corner, on its left and top edges (in), strictly inside the second triangle,
  // the tile-corner triangle and the fan triangle (b, b), (b − 10, b), (b, b − 10): 4. The
  // centre (64.5, 64.5) is on the second triangle's right and bottom edges (out), inside the
  // first and the tile-corner triangles, and the fan's centre vertex, where exactly one fan
  // triangle has a top and a left edge: 3.
  EXPECT_EQ(expected.count[size_t(kTileSize - 1) * w + kTileSize - 1], 4u);
  EXPECT_EQ(expected.count[size_t(kTileSize) * w + kTileSize], 3u);
  EXPECT_EQ(compare(expected, rasterized<false>(soup, w, h), soup, "tile boundary set"), 0u);
  EXPECT_EQ(compare(expected, rasterized<true>(soup, w, h), soup, "tile boundary set"), 0u);
}

TEST(ReferenceRasterizer, OnePixelViewport) {
  // The only pixel centre is (0.5, 0.5). A triangle whose top edge runs through it covers it; one
  // whose bottom edge runs through it does not; one whose left edge does, does; right, does not.
  const int w = 1, h = 1;
  struct Case {
    std::vector<std::array<double, 2>> pts;
    uint32_t expected;
  };
  const Case cases[] = {
      {{{-1.0, 0.5}, {2.0, 0.5}, {0.5, 2.0}}, 1},   // top edge
      {{{-1.0, 0.5}, {2.0, 0.5}, {0.5, -1.0}}, 0},  // bottom edge
      {{{0.5, -1.0}, {0.5, 2.0}, {2.0, 0.5}}, 1},   // left edge
      {{{0.5, -1.0}, {0.5, 2.0}, {-1.0, 0.5}}, 0},  // right edge
      {{{0.5, 0.5}, {2.0, 0.5}, {0.5, 2.0}}, 1},    // vertex on the centre, top-left corner
      {{{0.5, 0.5}, {-1.0, 0.5}, {0.5, -1.0}}, 0},  // vertex on the centre, bottom-right corner
      {{{0.0, 0.0}, {0.49, 0.0}, {0.0, 0.49}}, 0},  // inside the pixel, off its centre
      {{{-5.0, -5.0}, {9.0, -5.0}, {-5.0, 9.0}}, 1},
  };
  for (size_t i = 0; i < std::size(cases); ++i) {
    for (int winding = 0; winding < 2; ++winding) {
      ExactSoup soup = soup_from_pixels(
          cases[i].pts,
          winding == 0 ? std::vector<uint32_t>{0, 1, 2} : std::vector<uint32_t>{0, 2, 1}, w, h);
      EXPECT_EQ(reference(soup, w, h).count[0], cases[i].expected) << "case " << i;
      EXPECT_EQ(rasterized<false>(soup, w, h).count[0], cases[i].expected)
          << "case " << i << " winding " << winding;
    }
  }
}

TEST(ReferenceRasterizer, SliversAndZeroAreaTriangles) {
  const int w = 160, h = 96;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> px(-10.0, 170.0), py(-10.0, 106.0);
  // Zero area after snapping: collinear (also along a row of pixel centres), repeated vertices,
  // all three equal. No pixel, no depth written, each counted as degenerate.
  {
    ExactSoup soup = soup_from_pixels({{10.5, 10.5},
                                  {50.5, 30.5},
                                  {90.5, 50.5},  // collinear, on centres
                                  {0.5, 40.5},
                                  {80.5, 40.5},
                                  {150.5, 40.5},  // along a centre row
                                  {20, 20},
                                  {20, 20},
                                  {60, 70},  // repeated vertex
                                  {33.5, 33.5},
                                  {33.5, 33.5},
                                  {33.5, 33.5}},  // a point
                                 {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, w, h);
    RasterStats st;
    DepthTarget depth;
    const CoverageSets c = rasterized<false>(soup, w, h, &st, &depth);
    for (uint32_t n : c.count) ASSERT_EQ(n, 0u);
    for (float iw : depth.inv_w) ASSERT_EQ(iw, 0.0f);
    EXPECT_EQ(st.triangles_in, 4u);
    EXPECT_EQ(st.dropped_degenerate, 4u);
    EXPECT_EQ(st.setups, 0u);
  }
  // Slivers: two far-apart vertices and a third within a few subpixels of the line through
  // them (on either side, or exactly on it), at different depths. Coverage as the reference
  // says (a handful of centres at most), every depth written finite and within the range of
  // the vertices' 1/w (1/w is affine on the screen, so inside a triangle it interpolates them).
  for (int rep = 0; rep < 200; ++rep) {
    const double ax = px(rng), ay = py(rng), bx = px(rng), by = py(rng);
    const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const double len = std::hypot(bx - ax, by - ay);
    const double off = (int(rng() % 9) - 4) / 256.0;  // −4 … 4 subpixels across the line
    const double cx = ax + t * (bx - ax) - off * (by - ay) / len;
    const double cy = ay + t * (by - ay) + off * (bx - ax) / len;
    ExactSoup soup = soup_from_pixels({{ax, ay}, {bx, by}, {cx, cy}}, {0, 1, 2}, w, h);
    DepthTarget depth;
    const CoverageSets expected = reference(soup, w, h);
    const CoverageSets actual = rasterized<false>(soup, w, h, nullptr, &depth);
    ASSERT_EQ(compare(expected, actual, soup, "sliver " + std::to_string(rep)), 0u);
    float lo = 1e30f, hi = 0.0f;
    for (const ExactVertex& v : soup.vertices[0]) {
      lo = std::min(lo, -1.0f / v.position.z);
      hi = std::max(hi, -1.0f / v.position.z);
    }
    for (float iw : depth.inv_w) ASSERT_EQ(iw, 0.0f) << "every fragment was discarded";
    // Depth of the covered centres, this time with depth writes.
    DepthTarget written;
    DepthOnlyShader keep;
    rasterize(soup.views(), projection(), CullMode::None, w, h, written, keep);
    for (size_t i = 0; i < written.inv_w.size(); ++i) {
      const float iw = written.inv_w[i];
      ASSERT_TRUE(std::isfinite(iw)) << "sliver " << rep << " pixel " << i;
      ASSERT_EQ(iw > 0.0f, expected.count[i] > 0) << "sliver " << rep << " pixel " << i;
      if (iw > 0.0f) {
        EXPECT_GE(iw, lo * (1.0f - 1e-5f)) << "sliver " << rep;
        EXPECT_LE(iw, hi * (1.0f + 1e-5f)) << "sliver " << rep;
      }
    }
  }
}

TEST(ReferenceRasterizer, NonFiniteVerticesAreDroppedAndCounted) {
  // A random soup with some vertices replaced by NaN, ±Inf, or a finite position whose clip z
  // overflows to +Inf (z = −3.4e38: p22·z > FLT_MAX). Every triangle using one is dropped and
  // counted in dropped_nonfinite; every other triangle is drawn exactly as the reference says
  // (same global indices); no NaN reaches the depth buffer.
  const int w = 130, h = 67;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (uint32_t seed = 100; seed < 104; ++seed) {
    ExactSoup soup = random_soup(seed, w, h, 200);
    std::mt19937 rng(seed);
    std::vector<std::vector<bool>> bad(soup.vertices.size());
    size_t bad_vertices = 0;
    for (size_t m = 0; m < soup.vertices.size(); ++m) {
      bad[m].assign(soup.vertices[m].size(), false);
      for (size_t v = 0; v < soup.vertices[m].size(); ++v) {
        if (rng() % 10 != 0) continue;
        vec3& p = soup.vertices[m][v].position;
        switch (rng() % 5) {
          case 0:
            p.x = nan;
            break;
          case 1:
            p.y = inf;
            break;
          case 2:
            p.z = -inf;
            break;
          case 3:
            p = vec3(nan);
            break;
          default:
            p = vec3(0.0f, 0.0f, -3.4e38f);
            break;
        }
        bad[m][v] = true;
        ++bad_vertices;
      }
    }
    ASSERT_GT(bad_vertices, 0u);
    size_t bad_triangles = 0;
    for (size_t m = 0; m < soup.indices.size(); ++m)
      for (size_t t = 0; t + 2 < soup.indices[m].size(); t += 3)
        if (bad[m][soup.indices[m][t]] || bad[m][soup.indices[m][t + 1]] ||
            bad[m][soup.indices[m][t + 2]])
          ++bad_triangles;
    RasterStats st;
    const CoverageSets actual = rasterized<false>(soup, w, h, &st);
    EXPECT_EQ(st.triangles_in, soup.triangle_count()) << "seed " << seed;
    EXPECT_EQ(st.dropped_nonfinite, bad_triangles) << "seed " << seed;
    EXPECT_EQ(compare(reference(soup, w, h, &bad), actual, soup, "seed " + std::to_string(seed)),
              0u);
    DepthTarget depth;
    DepthOnlyShader keep;
    rasterize(soup.views(), projection(), CullMode::None, w, h, depth, keep);
    for (float iw : depth.inv_w) ASSERT_TRUE(std::isfinite(iw) && iw >= 0.0f) << "seed " << seed;
  }
  // A NaN in the matrix makes every vertex non-finite: everything dropped, nothing drawn.
  ExactSoup soup = random_soup(7, w, h, 50);
  mat4 broken = projection();
  broken[3][0] = nan;
  RasterStats st;
  const CoverageSets c = rasterized<true>(soup, w, h, &st, nullptr, broken);
  EXPECT_EQ(st.dropped_nonfinite, soup.triangle_count());
  for (uint32_t n : c.count) ASSERT_EQ(n, 0u);
}

}  // namespace
}  // namespace shadowlab
