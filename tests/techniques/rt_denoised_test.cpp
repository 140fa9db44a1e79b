// rts: ray-traced shadows at a few samples per pixel and the à-trous denoiser
// (techniques/rt/rt_denoised.h, techniques/rt/atrous.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <random>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "techniques/rt/atrous.h"
#include "techniques/rt/rt_denoised.h"
#include "test_paths.h"
#include "test_scenes.h"

namespace shadowlab {
namespace rt_denoised_test {  // a named namespace: the unity build joins the tests of a folder

// A W × H guide of two planes facing the camera and the light: columns x < split at depth z0,
// the rest at depth z1, normals n0 and n1; every pixel filtered.
AtrousGuide two_planes(int w, int h, int split, float z0, float z1, vec3 n0, vec3 n1) {
  AtrousGuide g;
  g.width = w;
  g.height = h;
  const size_t n = size_t(w) * size_t(h);
  for (auto* v : {&g.z, &g.g, &g.nx, &g.ny, &g.nz, &g.f}) v->assign(n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      const bool left = x < split;
      g.z[p] = left ? z0 : z1;
      const vec3 nn = left ? n0 : n1;
      g.nx[p] = nn.x, g.ny[p] = nn.y, g.nz[p] = nn.z;
      g.f[p] = 1.0f;
    }
  return g;
}

ImageF halves(int w, int h, int split, float left, float right) {
  ImageF m(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at(x, y) = x < split ? left : right;
  return m;
}

const AtrousKernels& scalar_rows() { return atrous_kernels(Isa::scalar); }

TEST(Atrous, VectorRowsGiveTheScalarBits) {
  // A real GBuffer (edges, grazing planes, uncovered and facing-away pixels), odd sizes so that
  // rows end inside a vector, random values; every parameter path.
  const Scene scene = test::small_scene("cluttered", 101, 67);
  const GBuffer g = render_gbuffer(scene);
  const AtrousGuide guide = atrous_guide(g, scene.light.position);
  ImageF noisy(g.width, g.height);
  for (size_t i = 0; i < noisy.data.size(); ++i)
    noisy.data[i] = float(mix64(i * 7919u + 3u) % 9u) / 8.0f;
  for (const AtrousParams p : {AtrousParams{}, AtrousParams{5, 0.3f, 0, 0.0f}, AtrousParams{2, 4.0f, 3, 2.0f}}) {
    const ImageF want = atrous_denoise(noisy, guide, p, scalar_rows());
    size_t changed = 0;
    for (size_t i = 0; i < want.data.size(); ++i) changed += want.data[i] != noisy.data[i];
    EXPECT_GT(changed, want.data.size() / 4);
    for (const Isa isa : cpu_isas()) {
      const ImageF got = atrous_denoise(noisy, guide, p, atrous_kernels(isa));
      ASSERT_EQ(atrous_kernels(isa).isa, isa);
      EXPECT_EQ(0, std::memcmp(got.data.data(), want.data.data(), want.data.size() * 4))
          << isa_name(isa) << " iterations " << p.iterations;
    }
  }
}

TEST(Atrous, OnAFlatPlaneItIsTheB3AtrousConvolution) {
  // No edges, no value term: each iteration is the separable B3 kernel with holes, renormalized
  // at the border. The impulse response computed here in double, directly from that definition.
  const int w = 48, h = 40, iters = 3;
  const AtrousGuide guide = two_planes(w, h, w, 2.0f, 2.0f, vec3(0, 0, 1), vec3(0, 0, 1));
  ImageF impulse(w, h);
  impulse.at(20, 17) = 1.0f;
  impulse.at(3, 2) = 0.5f;  // near the border: renormalization
  AtrousParams p;
  p.iterations = iters;
  p.sigma_v = 0.0f;
  const ImageF got = atrous_denoise(impulse, guide, p, scalar_rows());
  std::vector<double> a(impulse.data.begin(), impulse.data.end()), b(a.size());
  const double k[5] = {1 / 16.0, 1 / 4.0, 3 / 8.0, 1 / 4.0, 1 / 16.0};
  for (int it = 0; it < iters; ++it) {
    const int s = 1 << it;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double sum = 0, ws = 0;
        for (int j = -2; j <= 2; ++j)
          for (int i = -2; i <= 2; ++i) {
            const int qx = x + i * s, qy = y + j * s;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            sum += k[i + 2] * k[j + 2] * a[size_t(qy) * w + qx];
            ws += k[i + 2] * k[j + 2];
          }
        b[size_t(y) * w + x] = sum / ws;
      }
    std::swap(a, b);
  }
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - double(got.data[i])));
  EXPECT_LT(worst, 2e-7);
  EXPECT_GT(a[size_t(17) * w + 20 + 4], 1e-3);  // the response reaches 4 pixels: not a no-op
}

TEST(Atrous, ADepthStepStopsTheFilter) {
  // Lit plane (1) behind, shadowed plane (0) in front, the same normal: without the depth term
  // the 0s would average with the 1s next to the step (about 0.3 at the step with 4 iterations).
  const int w = 64, h = 32, split = 32;
  const AtrousGuide guide = two_planes(w, h, split, 1.0f, 5.0f, vec3(0, 0, 1), vec3(0, 0, 1));
  AtrousParams p;
  p.sigma_v = 0.0f;  // the GBuffer alone must stop it
  const ImageF out = atrous_denoise(halves(w, h, split, 0.0f, 1.0f), guide, p, scalar_rows());
  for (int y = 0; y < h; ++y) {
    EXPECT_LT(out.at(split - 1, y), 1e-6f) << y;
    EXPECT_GT(out.at(split, y), 1.0f - 1e-6f) << y;
  }
}

TEST(Atrous, ANormalCreaseStopsTheFilter) {
  // One depth, two normals 90° apart: the normal term alone must keep the halves apart.
  const int w = 64, h = 32, split = 32;
  const AtrousGuide guide = two_planes(w, h, split, 3.0f, 3.0f, vec3(0, 0, 1), vec3(1, 0, 0));
  AtrousParams p;
  p.sigma_v = 0.0f;
  const ImageF out = atrous_denoise(halves(w, h, split, 0.0f, 1.0f), guide, p, scalar_rows());
  for (int y = 0; y < h; ++y) {
    EXPECT_LT(out.at(split - 1, y), 1e-6f) << y;
    EXPECT_GT(out.at(split, y), 1.0f - 1e-6f) << y;
  }
}

TEST(Atrous, AShadowEdgeOnAPlaneIsKeptByTheValueTerm) {
  // One plane, a sharp shadow edge (0 | 1) that the GBuffer cannot see, as a 64-sample estimate
  // (variance at the edge m(1 − m)/64 ≈ 0.0035): the value term keeps it (within 1 %), where the
  // GBuffer terms alone blur it over the kernel's reach. As a 1-sample estimate the same edge is
  // within the noise, and the filter softens it.
  const int w = 64, h = 32, split = 32;
  const AtrousGuide guide = two_planes(w, h, w, 2.0f, 2.0f, vec3(0, 0, 1), vec3(0, 0, 1));
  const ImageF edge = halves(w, h, split, 0.0f, 1.0f);
  AtrousParams p;
  p.samples = 64;
  const ImageF kept = atrous_denoise(edge, guide, p, scalar_rows());
  p.samples = 1;
  const ImageF soft = atrous_denoise(edge, guide, p, scalar_rows());
  EXPECT_GT(soft.at(split - 1, 16), 0.01f);  // 0.020 measured
  p.sigma_v = 0.0f;
  const ImageF blurred = atrous_denoise(edge, guide, p, scalar_rows());
  EXPECT_LT(kept.at(split - 1, 16), 0.01f);
  EXPECT_GT(kept.at(split, 16), 0.99f);
  EXPECT_GT(blurred.at(split - 1, 16), 0.2f);
}

TEST(Atrous, PixelsThatAreNotFilteredAreNeitherChangedNorTaps) {
  // The left half is facing away (f = 0, value 0 by the mask convention): it keeps its values
  // and lends none to the lit half.
  const int w = 40, h = 24, split = 20;
  AtrousGuide guide = two_planes(w, h, w, 2.0f, 2.0f, vec3(0, 0, 1), vec3(0, 0, 1));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < split; ++x) guide.f[size_t(y) * w + x] = 0.0f;
  AtrousParams p;
  p.sigma_v = 0.0f;
  uint64_t taps = 0;
  const ImageF out = atrous_denoise(halves(w, h, split, 0.0f, 1.0f), guide, p, scalar_rows(), &taps);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_EQ(out.at(x, y), x < split ? 0.0f : 1.0f) << x << "," << y;
  EXPECT_EQ(taps, uint64_t(w - split) * h * 25u * 4u);
}

TEST(Atrous, TheGuideFiltersCoveredPixelsFacingTheLightOnly) {
  const Scene scene = test::small_scene("default", 96, 72);
  const GBuffer g = render_gbuffer(scene);
  const AtrousGuide guide = atrous_guide(g, scene.light.position);
  size_t filtered = 0, away = 0;
  for (size_t p = 0; p < g.pixel_count(); ++p) {
    const bool facing = g.covered[p] && glm::dot(g.geo_normal[p], scene.light.position - g.position[p]) > 0.0f;
    EXPECT_EQ(guide.f[p], facing ? 1.0f : 0.0f);
    filtered += facing;
    away += g.covered[p] && !facing;
    if (facing) EXPECT_EQ(guide.z[p], g.depth[p]);
  }
  EXPECT_GT(filtered, g.pixel_count() / 2);
  EXPECT_GT(away, 0u);  // the scene has surfaces facing away: the guide is tested on both kinds
}

TEST(RtDenoised, RawSamplesAreTheReferencesRays) {
  // rts without a denoiser draws the reference's samples: the same mask as rt at that spp.
  const Scene scene = test::small_scene("contact", 120, 90);
  const GBuffer g = render_gbuffer(scene);
  for (int spp : {1, 3, 8}) {
    const ShadowResult a = test::run("rts:spp=" + std::to_string(spp), scene, g);
    const ShadowResult b = test::run("rt:spp=" + std::to_string(spp), scene, g);
    EXPECT_EQ(0, std::memcmp(a.mask.data.data(), b.mask.data.data(), a.mask.data.size() * 4)) << spp;
  }
}

TEST(RtDenoised, RaysAndTapsAreCounted) {
  const Scene scene = test::small_scene("default", 96, 72);
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult hard = test::run("rts:hard=1", scene, g);
  EXPECT_GT(hard.work.pixels_looked_up, 1000u);
  EXPECT_EQ(hard.work.rays, hard.work.pixels_looked_up);  // one ray per light-facing pixel
  const ShadowResult soft = test::run("rts:spp=6,denoise=atrous,iterations=3", scene, g);
  EXPECT_EQ(soft.work.pixels_looked_up, hard.work.pixels_looked_up);
  // Samples below a receiver's tangent plane are not rays: at most 6 per pixel, most of them.
  EXPECT_LE(soft.work.rays, 6u * soft.work.pixels_looked_up);
  EXPECT_GT(soft.work.rays, 5u * soft.work.pixels_looked_up);
  EXPECT_EQ(soft.work.filter_taps, 25u * 3u * soft.work.pixels_looked_up);
  EXPECT_DOUBLE_EQ(soft.lookup_ms, soft.rays_ms + soft.denoise_ms);
  // The notes give the rate of the rays' own time; the rate holds for times under 1 ms too.
  char rate[64];
  std::snprintf(rate, sizeof rate, "%.1f M rays/s", mrays_per_second(soft.work.rays, soft.rays_ms));
  EXPECT_NE(soft.notes.find(rate), std::string::npos) << soft.notes << " / " << rate;
  EXPECT_DOUBLE_EQ(mrays_per_second(1000, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(mrays_per_second(3000000, 20.0), 150.0);
  EXPECT_EQ(mrays_per_second(1000, 0.0), 0.0);
  EXPECT_EQ(soft.map_ms, 0.0);
}

TEST(RtDenoised, OneTwoAndSevenThreadsGiveTheSameMask) {
  // A soft light (a point light would trace one deterministic ray per pixel, whatever the seed).
  Scene scene = test::small_scene("foliage", 90, 70);
  scene.light.radius = 0.1f;
  const GBuffer g = render_gbuffer(scene);
  std::vector<ShadowResult> r;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    r.push_back(test::run("rts:spp=2,denoise=atrous,iterations=5", scene, g));
  }
  set_thread_count(2);
  for (size_t i = 1; i < r.size(); ++i)
    EXPECT_EQ(0, std::memcmp(r[0].mask.data.data(), r[i].mask.data.data(), r[0].mask.data.size() * 4));
}

TEST(RtDenoised, DenoisingLowersTheErrorOfASoftShadow) {
  // The denoised error against the raw error, against a 1024-spp reference, on a soft light
  // (radius 0.15 m) at 256 × 192. Measured: RMSE 0.0213 at 4 spp denoised, raw 0.0287 at 4 and
  // 0.0167 at 8 spp; at 1 spp 0.0701 denoised against 0.0814 raw (512 × 384). A denoiser that
  // does nothing, or blurs the shadows' edges away, fails.
  Scene scene = test::small_scene("default", 256, 192);
  scene.light.radius = 0.15f;
  const GBuffer g = render_gbuffer(scene);
  const ImageF ref = test::run("rt:spp=1024", scene, g).mask;
  auto rmse = [&](const std::string& spec) {
    const ImageF m = test::run(spec, scene, g).mask;
    double s = 0;
    for (size_t i = 0; i < m.data.size(); ++i) s += std::pow(double(m.data[i]) - ref.data[i], 2);
    return std::sqrt(s / double(m.data.size()));
  };
  const double raw4 = rmse("rts:spp=4"), raw8 = rmse("rts:spp=8");
  const double den4 = rmse("rts:spp=4,denoise=atrous");
  EXPECT_LT(den4, 0.8 * raw4);
  EXPECT_GT(den4, raw8);  // the equal-error count is below 2x at this size (docs/results/rts.md)
  EXPECT_LT(raw8, 0.7 * raw4);  // the raw estimate converges
}

}  // namespace rt_denoised_test

namespace rt_denoised_definition_test {

using rt_denoised_test::scalar_rows;

// A W × H guide of one plane tilted in x (z = 2 + a·x, the gradient a set directly), normals
// (0, 0, 1): every term of the filter has a value known from its definition.
AtrousGuide tilted_plane(int w, int h, float a) {
  AtrousGuide g;
  g.width = w;
  g.height = h;
  const size_t n = size_t(w) * size_t(h);
  for (auto* v : {&g.z, &g.g, &g.nx, &g.ny, &g.nz, &g.f}) v->assign(n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      g.z[p] = 2.0f + a * float(x);
      g.g[p] = a;
      g.nz[p] = 1.0f;
      g.f[p] = 1.0f;
    }
  return g;
}

TEST(Atrous, TwoPassesFollowTheDocumentedWeightsAndVariance) {
  // The filter of techniques/rt/atrous.h evaluated here in double from its documented terms: the
  // binomial variance m(1 − m)/n of the 3 × 3 mean, the depth term with the tap's offset length,
  // the value term, and the variance carried as Σ w²·var / (Σ w)².
  const int w = 23, h = 17, n = 4;
  const float a = 0.05f;
  const AtrousGuide guide = tilted_plane(w, h, a);
  ImageF noisy(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) noisy.at(x, y) = float(mix64(uint64_t(y * 131 + x)) % 5u) / 4.0f;
  AtrousParams p;
  p.iterations = 2;
  p.sigma_z = 0.7f;
  p.sigma_v = 1.5f;
  p.samples = n;
  const ImageF got = atrous_denoise(noisy, guide, p, scalar_rows());

  auto at = [&](int x, int y) { return size_t(y) * size_t(w) + size_t(x); };
  std::vector<double> v(noisy.data.begin(), noisy.data.end()), var(v.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0, c = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (x + dx >= 0 && y + dy >= 0 && x + dx < w && y + dy < h) s += v[at(x + dx, y + dy)], c += 1;
      const double m = s / c;
      var[at(x, y)] = m * (1 - m) / n;
    }
  const double k[5] = {1 / 16.0, 1 / 4.0, 3 / 8.0, 1 / 4.0, 1 / 16.0};
  for (int it = 0; it < p.iterations; ++it) {
    const int step = 1 << it;
    std::vector<double> v2(v.size()), var2(v.size());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double sum = 0, ws = 0, vs = 0;
        for (int j = -2; j <= 2; ++j)
          for (int i = -2; i <= 2; ++i) {
            const int qx = x + i * step, qy = y + j * step;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const double dz = std::fabs(double(guide.z[at(x, y)]) - double(guide.z[at(qx, qy)]));
            const double off = step * std::sqrt(double(i * i + j * j));
            const double depth = dz / (double(a) * double(p.sigma_z) * off + 1e-4);
            const double value = std::fabs(v[at(x, y)] - v[at(qx, qy)]) /
                                 (double(p.sigma_v) * std::sqrt(var[at(x, y)]) + 1e-4);
            const double wt = k[i + 2] * k[j + 2] * std::exp(-(depth + value));
            sum += wt * v[at(qx, qy)];
            ws += wt;
            vs += wt * wt * var[at(qx, qy)];
          }
        v2[at(x, y)] = sum / ws;
        var2[at(x, y)] = vs / (ws * ws);
      }
    v.swap(v2);
    var.swap(var2);
  }
  double worst = 0, moved = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    worst = std::max(worst, std::fabs(v[i] - double(got.data[i])));
    moved = std::max(moved, std::fabs(v[i] - double(noisy.data[i])));
  }
  EXPECT_LT(worst, 2e-6);
  EXPECT_GT(moved, 0.1);  // the filter changes the values: the comparison is not of two no-ops
}

TEST(Atrous, TheGuidesGradientIsTheCentralDifferenceOrOneSidedAtAHole) {
  // z = 2 + 0.01·x² on a plane facing the camera and the light: the central difference at
  // column x is 0.02·x, the one-sided one at column 0 is 0.01, and next to an unfiltered pixel
  // (a hole in row 0 only) the other side's difference.
  const int w = 12, h = 6;
  GBuffer g;
  g.resize(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      const bool hole = y == 0 && x == 5;
      g.covered[p] = hole ? 0 : 1;
      g.depth[p] = 2.0f + 0.01f * float(x * x);
      g.position[p] = vec3(float(x), float(y), 0.0f);
      g.geo_normal[p] = vec3(0.0f, 0.0f, 1.0f);
    }
  const AtrousGuide guide = atrous_guide(g, vec3(5.0f, 3.0f, 10.0f));
  auto z = [](int x) { return 2.0f + 0.01f * float(x * x); };
  for (int y = 1; y < h; ++y) {
    EXPECT_FLOAT_EQ(guide.g[size_t(y) * w + 0], z(1) - z(0)) << y;
    EXPECT_FLOAT_EQ(guide.g[size_t(y) * w + 1], (z(2) - z(0)) / 2) << y;
    EXPECT_FLOAT_EQ(guide.g[size_t(y) * w + 6], (z(7) - z(5)) / 2) << y;
    EXPECT_FLOAT_EQ(guide.g[size_t(y) * w + w - 1], z(w - 1) - z(w - 2)) << y;
  }
  EXPECT_FLOAT_EQ(guide.g[6], z(7) - z(6));  // row 0, right of the hole: one-sided
  EXPECT_FLOAT_EQ(guide.g[4], z(4) - z(3));  // left of it
  EXPECT_EQ(guide.f[5], 0.0f);
}

TEST(Atrous, TheGuidesVerticalGradientSkipsAHoleBelowOrAbove) {
  // z = 2 + 0.2·y²: the vertical central difference at row y is 0.4·y; next to the hole at
  // (5, 0) the pixel (5, 1) takes the one-sided difference downwards.
  const int w = 12, h = 6;
  GBuffer g;
  g.resize(w, h);
  auto z = [](int y) { return 2.0f + 0.2f * float(y * y); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      g.covered[p] = (y == 0 && x == 5) ? 0 : 1;
      g.depth[p] = z(y);
      g.position[p] = vec3(float(x), float(y), 0.0f);
      g.geo_normal[p] = vec3(0.0f, 0.0f, 1.0f);
    }
  const AtrousGuide guide = atrous_guide(g, vec3(5.0f, 3.0f, 10.0f));
  EXPECT_FLOAT_EQ(guide.g[size_t(1) * w + 5], z(2) - z(1));
  EXPECT_FLOAT_EQ(guide.g[size_t(1) * w + 4], (z(2) - z(0)) / 2);
  EXPECT_FLOAT_EQ(guide.g[size_t(3) * w + 5], (z(4) - z(2)) / 2);
  EXPECT_FLOAT_EQ(guide.g[size_t(h - 1) * w + 2], z(h - 1) - z(h - 2));
}

TEST(Atrous, TheParametersDefaultsAreTheKeysDefaults) {
  // Code that filters with AtrousParams{} gets what rts:denoise=atrous declares.
  const AtrousParams d;
  const RtDenoisedParams k = parse_rt_denoised(parse_technique_spec("rts:denoise=atrous", "t"), "t");
  EXPECT_EQ(d.iterations, k.atrous.iterations);
  EXPECT_EQ(d.sigma_z, k.atrous.sigma_z);
  EXPECT_EQ(d.normal_power, k.atrous.normal_power);
  EXPECT_EQ(d.sigma_v, k.atrous.sigma_v);
  EXPECT_EQ(d.normal_power, 7);  // SVGF's power 128
  EXPECT_EQ(k.spp, 4);
}

TEST(AtrousDeathTest, ParametersOutsideTheirRangesAreProgrammerErrors) {
  const AtrousGuide guide = tilted_plane(8, 8, 0.1f);
  const ImageF m(8, 8, 1, 0.5f);
  AtrousParams p;
  p.normal_power = 11;
  EXPECT_DEATH(atrous_denoise(m, guide, p, scalar_rows()), "CHECK");
  p.normal_power = 7;
  p.iterations = 11;
  EXPECT_DEATH(atrous_denoise(m, guide, p, scalar_rows()), "CHECK");
}

TEST(KeysPage, TheReviewedPageIsWhatTheDeclarationsSay) {
  // docs/techniques/keys.md was reviewed; every key's default, range and help comes from its
  // declaration, so a changed declaration changes the page.
  std::ifstream f(test::source_path("docs/techniques/keys.md"));
  ASSERT_TRUE(f);
  std::stringstream ss;
  ss << f.rdbuf();
  // The page is the declarations' text, then tune's default spaces (lab/param_space.h).
  const std::string page = ss.str(), keys = technique_keys_markdown();
  EXPECT_EQ(page.substr(0, keys.size()), keys) << "run bash docs/techniques/keys.sh";
  const std::string next = "\n## tune's default spaces\n";
  EXPECT_EQ(page.compare(keys.size(), next.size(), next), 0);
}

}  // namespace rt_denoised_definition_test
}  // namespace shadowlab
