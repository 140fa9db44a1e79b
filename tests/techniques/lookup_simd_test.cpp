// The SIMD lookup kernels against their scalar oracle, byte for byte, at the comparison's
// threshold: each receiver's own texel holds exactly the depth the scalar path computes for it
// (make_receiver), so a kernel whose receiver depth differs by one ulp flips that receiver.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>

#include "core/isa.h"
#include "techniques/pipeline/light_map.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {
namespace {

struct Case {
  Scene scene;
  GBuffer g;
};

// n random receivers around a light at (0.3, 1.2, -0.4), range 15 m, with random normals facing
// the light (some facing away, some uncovered), plus the tetrahedron's exact tie directions.
Case random_case(int n, uint32_t seed, bool projector) {
  Case c;
  c.scene.materials.push_back(Material{});
  c.scene.light.position = vec3(0.3f, 1.2f, -0.4f);
  c.scene.light.far = 15.0f;
  if (projector) {
    Projector& pr = c.scene.projector;
    pr.enabled = true;
    pr.position = c.scene.light.position;
    pr.direction = vec3(0.2f, -1.0f, 0.3f);
    pr.up = vec3(0.0f, 0.0f, 1.0f);
    pr.fov_y_deg = 70.0f;
    pr.aspect = 1.3f;
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  c.g.resize(n, 1);
  const vec3 ties[4] = {{0, -1, 0}, {0, 1, 0}, {-1, 0, 1}, {1, 0, -1}};
  for (int i = 0; i < n; ++i) {
    vec3 dir(u(rng), u(rng), u(rng));
    if (i < 16) dir = ties[i % 4];
    if (projector && i % 3 != 0) dir = vec3(0.2f, -1.0f, 0.3f) + 0.4f * vec3(u(rng), 0.0f, u(rng));
    dir = glm::normalize(dir);
    const float dist = 0.5f + 6.0f * (u(rng) + 1.0f);
    const vec3 p = c.scene.light.position + dist * dir;
    vec3 nrm = glm::normalize(-dir + 0.8f * vec3(u(rng), u(rng), u(rng)));
    if (i % 17 == 5) nrm = -nrm;  // may face away
    c.g.position[size_t(i)] = p;
    c.g.normal[size_t(i)] = c.g.geo_normal[size_t(i)] = nrm;
    c.g.covered[size_t(i)] = i % 23 != 7;
  }
  return c;
}

// The map: random stored depths, and each receiver's own texel set to its scalar depth.
LightMap threshold_map(const Case& c, const MapParams& p, uint32_t seed) {
  LightMap map;
  map.layout = map_layout(p, c.scene);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const size_t nf = map.layout.faces.size();
  map.dist.distance.resize(nf);
  map.dist.rendered.assign(nf, true);
  for (size_t f = 0; f < nf; ++f) {
    map.dist.distance[f].resize(map.layout.faces[f].texel_count());
    for (float& d : map.dist.distance[f]) d = u(rng);
  }
  const float inv_far = 1.0f / c.scene.light.far;
  for (size_t i = 0; i < c.g.pixel_count(); ++i) {
    if (!c.g.covered[i] || !faces_light(c.g, i, c.scene.light.position)) continue;
    const Receiver r = make_receiver(map.layout, c.scene.light, p, map_reach(p), inv_far,
                                     c.g.position[i], c.g.geo_normal[i]);
    const size_t per_face = map.layout.faces[0].texel_count();
    map.dist.distance[size_t(r.face)][r.texel - size_t(r.face) * per_face] = r.depth;
  }
  return map;
}

void lookup_with(const char* scalar, const Case& c, const MapParams& p, const LightMap& map,
                 ImageF& mask, ImageU32& texels) {
  const ScopedIsa isa(std::string(scalar) == "1" ? Isa::scalar : cpu_isa());
  lookup_light_map(c.scene, c.g, p, map, mask, &texels);
}

TEST(LookupSimd, KernelsMatchTheScalarOracleAtTheThreshold) {
  if (cpu_isa() < Isa::avx2) GTEST_SKIP() << "no AVX2 on this CPU";
  struct Config {
    FaceLayoutKind layout;
    float bias, slope;
    int pcf;
  };
  // pcf > 1: the vector N×N loop for footprints inside a face (with cross seams on the cube,
  // footprints at a face's edge go to the scalar walk; the guard-band layouts keep all inside).
  for (const Config& cfg : {Config{FaceLayoutKind::Cube, 0.01f, 1.0f, 1}, Config{FaceLayoutKind::Cube, 0.0f, 0.0f, 1},
                            Config{FaceLayoutKind::Cube, 0.01f, 1.0f, 3},
                            Config{FaceLayoutKind::Tetrahedron, 0.01f, 1.0f, 1},
                            Config{FaceLayoutKind::Tetrahedron, 0.003f, 2.5f, 1},
                            Config{FaceLayoutKind::Tetrahedron, 0.003f, 2.5f, 5},
                            Config{FaceLayoutKind::Projector, 0.01f, 1.0f, 1},
                            Config{FaceLayoutKind::Projector, 0.01f, 1.0f, 3},
                            Config{FaceLayoutKind::DualParaboloid, 0.01f, 1.0f, 1},
                            Config{FaceLayoutKind::DualParaboloid, 0.003f, 2.5f, 3}}) {
    const bool projector = cfg.layout == FaceLayoutKind::Projector;
    const Case c = random_case(4096, 7, projector);
    MapParams p = default_map_params(cfg.layout, MapFilter::Depth);
    p.res = 64;
    p.bias = cfg.bias;
    p.slope = cfg.slope;
    p.pcf = cfg.pcf;
    const LightMap map = threshold_map(c, p, 11);
    ImageF scalar_mask, simd_mask;
    ImageU32 scalar_texels, simd_texels;
    lookup_with("1", c, p, map, scalar_mask, scalar_texels);
    lookup_with("0", c, p, map, simd_mask, simd_texels);
    const std::string what = "layout " + std::to_string(int(cfg.layout)) + " slope " +
                             std::to_string(cfg.slope) + " pcf " + std::to_string(cfg.pcf);
    ASSERT_EQ(scalar_mask.data.size(), simd_mask.data.size());
    EXPECT_EQ(std::memcmp(scalar_mask.data.data(), simd_mask.data.data(), scalar_mask.data.size() * 4), 0) << what;
    EXPECT_EQ(std::memcmp(scalar_texels.data.data(), simd_texels.data.data(), scalar_texels.data.size() * 4), 0) << what;
    // Not vacuous: most looked-up receivers sit exactly on their threshold and are lit, and
    // the random texels around them shadow others.
    size_t lit = 0, partial = 0, looked = 0;
    for (size_t i = 0; i < c.g.pixel_count(); ++i) {
      if (scalar_texels.data[i] == kNoTexel) continue;
      ++looked;
      lit += scalar_mask.data[i] == 1.0f;
      partial += scalar_mask.data[i] > 0.0f && scalar_mask.data[i] < 1.0f;
    }
    EXPECT_GT(looked, c.g.pixel_count() / 4) << what;
    if (cfg.pcf == 1)
      EXPECT_GT(lit, looked / 2) << what;
    else
      EXPECT_GT(partial, looked / 2) << what;
  }
}

// The filtering techniques' 8-lane batches (VSM, ESM, EVSM, MSM, rotated Poisson PCF, PCSS:
// gathers, then the arithmetic of techniques/lookup/lookup_batches.h) of every vector table this CPU has
// against their scalar oracle on random maps, blurred by their own filter: bit for bit.
TEST(LookupSimd, FilterBatchesMatchTheScalarOracle) {
  if (cpu_isa() < Isa::avx2) GTEST_SKIP() << "no AVX2 on this CPU";
  struct Config {
    FaceLayoutKind layout;
    MapFilter filter;
    int moments;
    double bleed;
    MsmKeys msm = {};
    int poisson_pcf = 0;  // > 0: depth compare with rotated Poisson PCF of this width
  };
  for (const Config& cfg : {Config{FaceLayoutKind::Cube, MapFilter::ExponentialVariance, 2, 0.0},
                            Config{FaceLayoutKind::Cube, MapFilter::ExponentialVariance, 4, 0.2},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::ExponentialVariance, 4, 0.0},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::ExponentialVariance, 2, 0.3},
                            Config{FaceLayoutKind::Cube, MapFilter::Variance, 2, 0.2},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::Exponential, 2, 0.0},
                            Config{FaceLayoutKind::Cube, MapFilter::Moment, 2, 0.0},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::Moment, 2, 0.0,
                                   MsmKeys{true, false, 3e-6}},
                            Config{FaceLayoutKind::Cube, MapFilter::Moment, 2, 0.0,
                                   MsmKeys{true, true, 3e-5}},
                            Config{FaceLayoutKind::Cube, MapFilter::Moment, 2, 0.0,
                                   MsmKeys{false, false, 0.0}},
                            Config{FaceLayoutKind::Cube, MapFilter::Depth, 2, 0.0, {}, 5},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::Depth, 2, 0.0, {}, 3},
                            Config{FaceLayoutKind::DualParaboloid, MapFilter::Variance, 2, 0.1},
                            Config{FaceLayoutKind::DualParaboloid, MapFilter::Depth, 2, 0.0, {}, 5},
                            Config{FaceLayoutKind::Cube, MapFilter::Pcss, 2, 0.0},
                            Config{FaceLayoutKind::Tetrahedron, MapFilter::Pcss, 2, 0.0},
                            Config{FaceLayoutKind::DualParaboloid, MapFilter::Pcss, 2, 0.0},
                            Config{FaceLayoutKind::Cube, MapFilter::Pcss, 4, 0.0}}) {
    const Case c = random_case(4096, 5, false);
    MapParams p = default_map_params(cfg.layout, cfg.filter);
    p.res = 64;
    p.evsm.moments = cfg.moments;
    p.evsm.bleed = p.vsm.bleed = cfg.bleed;
    p.evsm.c_pos = 20.0;  // the random depths' spread: bounds strictly inside (0, 1)
    p.msm = cfg.msm;
    p.pcss.light_size = 0.2;                           // penumbrae several texels wide
    if (cfg.filter == MapFilter::Pcss && cfg.moments == 4) p.rpdb = false;  // the slope-bias form
    if (cfg.poisson_pcf > 0) {
      p.pcf = cfg.poisson_pcf;
      p.pcf_kind = PcfKind::Poisson;
      p.seams = SeamMode::Guard;
    }
    LightMap map = threshold_map(c, p, 13);
    filter_light_map(p, map);
    ImageF scalar_mask, simd_mask;
    ImageU32 scalar_texels, simd_texels;
    lookup_with("1", c, p, map, scalar_mask, scalar_texels);
    const std::string what = "filter " + std::to_string(int(cfg.filter)) + " layout " +
                             std::to_string(int(cfg.layout)) + " moments " +
                             std::to_string(cfg.moments) + " msm " +
                             std::to_string(cfg.msm.hausdorff) + std::to_string(cfg.msm.quantize16);
    // Every vector table this CPU has (the lookup's and techniques/lookup/lookup_batches.h's).
    for (const Isa isa : cpu_isas()) {
      if (isa == Isa::scalar) continue;
      const ScopedIsa guard(isa);
      lookup_light_map(c.scene, c.g, p, map, simd_mask, &simd_texels);
      EXPECT_EQ(std::memcmp(scalar_mask.data.data(), simd_mask.data.data(),
                            scalar_mask.data.size() * 4), 0) << what << " " << isa_name(isa);
    }
    // Not vacuous: both branches of the bound (receiver in front: 1; behind: a fraction) occur
    // on many receivers (measured 64-94 fractions of 4096 on the sparsest configurations).
    size_t partial = 0, lit = 0;
    for (const float v : scalar_mask.data) {
      partial += v > 0.0f && v < 1.0f;
      lit += v == 1.0f;
    }
    EXPECT_GT(partial, c.g.pixel_count() / 100) << what;
    EXPECT_GT(lit, c.g.pixel_count() / 100) << what;
  }
}

}  // namespace
}  // namespace shadowlab

namespace shadowlab {
namespace {

// 8 receivers on faces 0–2 (1, 2 and 9 texels wide in the tests below) at coordinates that are
// often exactly on or near a texel edge or outside the face, a fifth of the lanes inactive.
// Faces 0 and 1 only in every fourth batch, so the wide-load paths run on the others.
Receivers8 edge_receivers(std::mt19937& rng, int trial) {
  std::uniform_real_distribution<float> u(-2.0f, 12.0f);
  const float edges[] = {-3.0f, -0.5f, 0.0f, 0.49f, 0.5f, 0.51f, 1.0f, 1.5f, 2.5f, 8.5f, 9.0f, 9.5f, 20.0f};
  Receivers8 r{};
  for (int k = 0; k < 8; ++k) {
    r.face[k] = trial % 4 == 0 ? int32_t(rng() % 3) : 2;
    r.sx[k] = rng() % 2 ? edges[rng() % 13] : u(rng);
    r.sy[k] = rng() % 2 ? edges[rng() % 13] : u(rng);
    r.active[k] = rng() % 5 ? -1 : 0;
  }
  return r;
}

// The bilinear tap loads (bilinear8_simd: adjacent taps loaded as pairs) against
// bilinear_taps + bilinear_indices, on faces 1, 2 and 9 texels wide, with lanes clamped at
// every edge, inactive lanes, and two planes whose texel values are all distinct.
TEST(LookupSimd, BilinearTapsMatchTheScalarTapsAtEveryEdge) {
  const Bilinear8Fn bilinear8 = lookup_kernels(cpu_isa()).bilinear8;
  if (!bilinear8) GTEST_SKIP() << "no AVX2 here (or SHADOWLAB_SCALAR=1)";
  const int widths[3] = {1, 2, 9}, heights[3] = {3, 1, 5};
  MapLookupConsts c;
  std::vector<std::vector<float>> planes(2);
  for (int p = 0; p < 2; ++p)
    for (int f = 0; f < 3; ++f)
      for (int i = 0; i < widths[f] * heights[f]; ++i)
        planes[p].push_back(float(1000 * p + 100 * f + i));
  PlaneGather g[2];
  for (int p = 0; p < 2; ++p) {
    g[p].base = planes[p].data();
    int off = 0;
    for (int f = 0; f < 3; ++f) {
      g[p].offset[f] = off;
      off += widths[f] * heights[f];
    }
    g[p].ok = true;
  }
  for (int f = 0; f < 3; ++f) {
    c.width[f] = widths[f];
    c.height[f] = heights[f];
  }
  std::mt19937 rng(5);
  int checked = 0, clamped_left = 0, clamped_right = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Receivers8 r = edge_receivers(rng, trial);
    alignas(32) float values[2][4][8], fx[8], fy[8];
    bilinear8(c, r, g, 2, values, fx, fy);
    for (int k = 0; k < 8; ++k) {
      if (!r.active[k]) continue;
      const int f = r.face[k];
      const Bilinear b = bilinear_taps(vec2(r.sx[k], r.sy[k]), widths[f], heights[f]);
      size_t idx[4];
      bilinear_indices(b, widths[f], idx);
      ASSERT_EQ(fx[k], b.fx);
      ASSERT_EQ(fy[k], b.fy);
      for (int p = 0; p < 2; ++p)
        for (int t = 0; t < 4; ++t)
          ASSERT_EQ(values[p][t][k], planes[p][size_t(g[p].offset[f]) + idx[t]])
              << "trial " << trial << " lane " << k << " plane " << p << " tap " << t;
      ++checked;
      clamped_left += floor_int(r.sx[k] - 0.5f) < 0;
      clamped_right += floor_int(r.sx[k] - 0.5f) >= widths[f] - 1;
    }
  }
  EXPECT_GT(checked, 20000);
  EXPECT_GT(clamped_left, 1000);
  EXPECT_GT(clamped_right, 1000);
}

// The interleaved kernels (VSM's and EVSM's mean and variance, N = 2; MSM's four moments,
// N = 4) against the scalar taps: each lane's 4 taps × N values are the clamped footprint's
// texels (bilinear_taps), read at N·i + v, with faces 1, 2 and 9 texels wide so the
// lane-by-lane fallback, the edge-clamped lanes and the wide loads all run.
void check_interleaved_taps(Bilinear8x2Fn kernel, int n_values) {
  const int widths[3] = {1, 2, 9}, heights[3] = {3, 1, 5};
  MapLookupConsts c;
  std::vector<float> plane;
  PlaneGather g;
  for (int f = 0; f < 3; ++f) {
    g.offset[f] = int32_t(plane.size());
    for (int i = 0; i < widths[f] * heights[f]; ++i)
      for (int v = 0; v < n_values; ++v) plane.push_back(float(5000 * v + 100 * f + i));
    c.width[f] = widths[f];
    c.height[f] = heights[f];
  }
  g.base = plane.data();
  g.ok = true;
  std::mt19937 rng(7);
  int checked = 0, clamped_left = 0, clamped_right = 0, fast_batches = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Receivers8 r = edge_receivers(rng, trial);
    bool narrow = false;
    for (int k = 0; k < 8; ++k) narrow |= r.active[k] && r.face[k] == 0;
    fast_batches += !narrow;
    alignas(32) float values[4][4][8], fx[8], fy[8];
    kernel(c, r, g, values, fx, fy);
    for (int k = 0; k < 8; ++k) {
      if (!r.active[k]) continue;
      const int f = r.face[k];
      const Bilinear b = bilinear_taps(vec2(r.sx[k], r.sy[k]), widths[f], heights[f]);
      size_t idx[4];
      bilinear_indices(b, widths[f], idx);
      ASSERT_EQ(fx[k], b.fx);
      ASSERT_EQ(fy[k], b.fy);
      for (int v = 0; v < n_values; ++v)
        for (int t = 0; t < 4; ++t)
          ASSERT_EQ(values[v][t][k], plane[size_t(g.offset[f]) + size_t(n_values) * idx[t] + size_t(v)])
              << n_values << " values, trial " << trial << " lane " << k << " value " << v
              << " tap " << t;
      ++checked;
      clamped_left += floor_int(r.sx[k] - 0.5f) < 0;
      clamped_right += floor_int(r.sx[k] - 0.5f) >= widths[f] - 1;
    }
  }
  EXPECT_GT(checked, 20000);
  EXPECT_GT(clamped_left, 1000);
  EXPECT_GT(clamped_right, 1000);
  EXPECT_GT(fast_batches, 2000);
}

TEST(LookupSimd, InterleavedBilinearTapsMatchTheScalarTapsAtEveryEdge) {
  const LookupKernels& kernels = lookup_kernels(cpu_isa());
  const Bilinear8x2Fn two = kernels.bilinear8_interleaved2, four = kernels.bilinear8_interleaved4;
  if (!two || !four) GTEST_SKIP() << "no AVX2 here (or SHADOWLAB_SCALAR=1)";
  check_interleaved_taps(two, 2);
  check_interleaved_taps(four, 4);
}

// The AVX2 bilinear mix of four values per texel (MSM's moments) against a sum written out here
// from the scalar taps: each active lane's m[v] = ((((0 + w0·v0) + w1·v1) + w2·v2) + w3·v3) in
// double with bilinear_weights' w, bit for bit, on faces 1, 2 and 9 texels wide (the lane-by-lane
// fallback, the edge-clamped lanes and the wide loads), and zeros in the inactive lanes.
TEST(LookupSimd, BilinearMixOfFourValuesIsTheScalarSumAtEveryEdge) {
  const Mix8x4Fn mix = lookup_kernels(cpu_isa()).bilinear8_mix4;
  if (!mix) GTEST_SKIP() << "no AVX2 here (or SHADOWLAB_SCALAR=1)";
  const int widths[3] = {1, 2, 9}, heights[3] = {3, 1, 5};
  MapLookupConsts c;
  std::vector<float> plane;
  PlaneGather g;
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int f = 0; f < 3; ++f) {
    g.offset[f] = int32_t(plane.size());
    // Moments of a random depth: values whose products with the weights round.
    for (int i = 0; i < widths[f] * heights[f]; ++i) {
      const float d = u(rng);
      for (const float v : {d, d * d, d * d * d, d * d * d * d}) plane.push_back(v);
    }
    c.width[f] = widths[f];
    c.height[f] = heights[f];
  }
  g.base = plane.data();
  g.ok = true;
  int checked = 0, inexact = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Receivers8 r = edge_receivers(rng, trial);
    alignas(32) double m[4][8];
    mix(c, r, g, m);
    for (int k = 0; k < 8; ++k) {
      if (!r.active[k]) {
        for (int v = 0; v < 4; ++v) ASSERT_EQ(m[v][k], 0.0) << "inactive lane " << k;
        continue;
      }
      const int f = r.face[k];
      const Bilinear b = bilinear_taps(vec2(r.sx[k], r.sy[k]), widths[f], heights[f]);
      size_t idx[4];
      bilinear_indices(b, widths[f], idx);
      const double w[4] = {(1.0 - b.fx) * (1.0 - b.fy), double(b.fx) * (1.0 - b.fy),
                           (1.0 - b.fx) * double(b.fy), double(b.fx) * double(b.fy)};
      for (int v = 0; v < 4; ++v) {
        double want = 0.0;
        for (int t = 0; t < 4; ++t) want += w[t] * plane[size_t(g.offset[f]) + 4 * idx[t] + size_t(v)];
        ASSERT_EQ(m[v][k], want) << "trial " << trial << " lane " << k << " value " << v;
        // A sum whose terms round: the order of the additions is what is tested.
        long double exact = 0.0L;
        for (int t = 0; t < 4; ++t)
          exact += (long double)w[t] * plane[size_t(g.offset[f]) + 4 * idx[t] + size_t(v)];
        inexact += (long double)want != exact;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 20000);
  EXPECT_GT(inexact, 4000);  // 8,485 of the ~90,000 sums here
}

// merge8 is the pixel loop's per-lane rule: active lanes get std::clamp(vis, 0, 1) (a NaN stays
// NaN, -0 stays -0), inactive lanes keep the receivers' mask; texels are copied.
TEST(LookupSimd, Merge8IsThePixelLoopsClampPerLane) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float vis_in[8] = {-1.0f, 0.5f, 2.0f, nan, -0.0f, 1.0f, inf, -inf};
  for (int pattern = 0; pattern < 256; pattern += 37) {
    Receivers8 r{};
    alignas(32) float vis[8];
    for (int k = 0; k < 8; ++k) {
      vis[k] = vis_in[k];
      r.active[k] = (pattern >> k) & 1 ? -1 : 0;
      r.mask[k] = k % 2 ? 1.0f : 0.0f;
      r.texel[k] = 100 + k;
    }
    float mask[8];
    uint32_t texels[8];
    for (const Isa isa : cpu_isas()) {
      lookup_kernels(isa).merge8(r, vis, mask, texels);
      for (int k = 0; k < 8; ++k) {
        const float want = r.active[k] ? std::clamp(vis[k], 0.0f, 1.0f) : r.mask[k];
        EXPECT_EQ(std::memcmp(&mask[k], &want, 4), 0)
            << "pattern " << pattern << " lane " << k << " " << isa_name(isa);
        EXPECT_EQ(texels[k], uint32_t(100 + k));
      }
    }
  }
}

}  // namespace
}  // namespace shadowlab
