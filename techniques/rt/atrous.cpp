#include "techniques/rt/atrous.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/exp_log.h"
#include "core/parallel.h"

namespace shadowlab {

#if defined(__x86_64__)
// The vector rows (techniques/rt/atrous_avx2.cpp, atrous_avx512.cpp).
namespace atrous_avx2 {
void row(const AtrousRow& r);
}
namespace atrous_avx512 {
void row(const AtrousRow& r);
}
#endif

namespace {

constexpr float kAtrousB3[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};

struct AtrousTapTable {
  float h[25];
  AtrousTapTable() {
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) h[j * 5 + i] = kAtrousB3[j] * kAtrousB3[i];
  }
};
const AtrousTapTable kAtrousTaps;

// The scalar row: the oracle of the vector rows, which do the same float operations in the same
// order per pixel (a tap outside the image, or on a pixel with f = 0, adds +0 there and is
// skipped here: the same sums).
void atrous_row_scalar(const AtrousRow& r) {
  const AtrousGuide& gd = *r.guide;
  const int w = gd.width, h = gd.height, y = r.y, s = r.step;
  const float* hw = atrous_tap_weights();
  for (int x = 0; x < w; ++x) {
    const size_t p = size_t(y) * size_t(w) + size_t(x);
    if (gd.f[p] == 0.0f) {
      r.out[p] = r.in[p];
      r.var_out[p] = r.var_in[p];
      continue;
    }
    const float vden = r.sigma_v * std::sqrt(r.var_in[p]) + kAtrousValueEps;
    const float vinv = r.sigma_v > 0.0f ? 1.0f / vden : 0.0f;
    float sum = 0.0f, wsum = 0.0f, vsum = 0.0f;
    for (int j = 0; j < 5; ++j) {
      const int qy = y + (j - 2) * s;
      if (qy < 0 || qy >= h) continue;
      for (int i = 0; i < 5; ++i) {
        const int qx = x + (i - 2) * s;
        if (qx < 0 || qx >= w) continue;
        const size_t q = size_t(qy) * size_t(w) + size_t(qx);
        const float dz = std::fabs(gd.z[p] - gd.z[q]);
        const float dv = std::fabs(r.in[p] - r.in[q]);
        const float arg = -(dz / (gd.g[p] * r.tap_c[j * 5 + i] + kAtrousDepthEps) + dv * vinv);
        const float e = exp_f(std::max(arg, kAtrousMinExponent));
        const float d = (gd.nx[p] * gd.nx[q] + gd.ny[p] * gd.ny[q]) + gd.nz[p] * gd.nz[q];
        float wn = d > 0.0f ? d : 0.0f;
        for (int k = 0; k < r.normal_power; ++k) wn = wn * wn;
        const float wt = ((hw[j * 5 + i] * e) * wn) * gd.f[q];
        sum = sum + wt * r.in[q];
        wsum = wsum + wt;
        vsum = vsum + (wt * wt) * r.var_in[q];
      }
    }
    r.out[p] = sum / wsum;
    r.var_out[p] = vsum / (wsum * wsum);
  }
}

constexpr AtrousKernels kAtrousScalar{Isa::scalar, atrous_row_scalar};
#if defined(__x86_64__)
constexpr AtrousKernels kAtrousAvx2{Isa::avx2, atrous_avx2::row};
constexpr AtrousKernels kAtrousAvx512{Isa::avx512, atrous_avx512::row};
#endif

}  // namespace

const float* atrous_tap_weights() { return kAtrousTaps.h; }

const AtrousKernels& atrous_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kAtrousAvx512;
  if (isa == Isa::avx2) return kAtrousAvx2;
#endif
  (void)isa;
  return kAtrousScalar;
}

AtrousGuide atrous_guide(const GBuffer& g, vec3 light) {
  AtrousGuide gd;
  gd.width = g.width;
  gd.height = g.height;
  const size_t n = g.pixel_count();
  for (auto* v : {&gd.z, &gd.g, &gd.nx, &gd.ny, &gd.nz, &gd.f}) v->assign(n, 0.0f);
  for (size_t p = 0; p < n; ++p) {
    if (!g.covered[p] || !(glm::dot(g.geo_normal[p], light - g.position[p]) > 0.0f)) continue;
    gd.f[p] = 1.0f;
    gd.z[p] = g.depth[p];
    gd.nx[p] = g.geo_normal[p].x;
    gd.ny[p] = g.geo_normal[p].y;
    gd.nz[p] = g.geo_normal[p].z;
  }
  // The depth gradient: the larger of the two axes' central differences (one-sided where a
  // neighbour is not filtered), in metres per pixel.
  const int w = g.width, h = g.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      if (gd.f[p] == 0.0f) continue;
      auto axis = [&](int dx, int dy) {
        float lo = gd.z[p], hi = gd.z[p];
        int span = 0;
        const int x0 = x - dx, y0 = y - dy, x1 = x + dx, y1 = y + dy;
        if (x0 >= 0 && y0 >= 0 && gd.f[size_t(y0) * size_t(w) + size_t(x0)] != 0.0f)
          lo = gd.z[size_t(y0) * size_t(w) + size_t(x0)], ++span;
        if (x1 < w && y1 < h && gd.f[size_t(y1) * size_t(w) + size_t(x1)] != 0.0f)
          hi = gd.z[size_t(y1) * size_t(w) + size_t(x1)], ++span;
        return span == 0 ? 0.0f : std::fabs(hi - lo) / float(span);
      };
      gd.g[p] = std::max(axis(1, 0), axis(0, 1));
    }
  return gd;
}

ImageF atrous_denoise(const ImageF& noisy, const AtrousGuide& guide, const AtrousParams& p,
                      const AtrousKernels& kernels, uint64_t* taps) {
  SL_CHECK(noisy.width == guide.width && noisy.height == guide.height && noisy.channels == 1);
  SL_CHECK(p.iterations >= 0 && p.iterations <= 10 && p.normal_power >= 0 && p.normal_power <= 10);
  SL_CHECK(p.samples >= 1);
  ImageF a = noisy, b(noisy.width, noisy.height);
  // The input's variance: binomial, m(1 − m)/n, m the mean of the 3 × 3 filtered neighbourhood.
  const int w = noisy.width, h = noisy.height;
  std::vector<float> va(noisy.data.size(), 0.0f), vb(noisy.data.size(), 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t c = size_t(y) * size_t(w) + size_t(x);
      if (guide.f[c] == 0.0f) continue;
      float sum = 0.0f, count = 0.0f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t q = size_t(qy) * size_t(w) + size_t(qx);
          if (guide.f[q] == 0.0f) continue;
          sum += noisy.data[q];
          count += 1.0f;
        }
      const float m = sum / count;
      va[c] = m * (1.0f - m) / float(p.samples);
    }
  for (int it = 0; it < p.iterations; ++it) {
    const int step = 1 << it;
    float tap_c[25];
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        tap_c[j * 5 + i] = p.sigma_z * float(step) *
                           std::sqrt(float((i - 2) * (i - 2) + (j - 2) * (j - 2)));
    // Rows in chunks whose boundaries depend on the height alone: any thread count gives the
    // same image (each row writes only its own pixels).
    parallel_for_chunks(size_t(noisy.height), 8, [&](size_t y0, size_t y1) {
      for (size_t y = y0; y < y1; ++y) {
        AtrousRow r;
        r.in = a.data.data();
        r.out = b.data.data();
        r.guide = &guide;
        r.y = int(y);
        r.step = step;
        r.tap_c = tap_c;
        r.normal_power = p.normal_power;
        r.sigma_v = p.sigma_v;
        r.var_in = va.data();
        r.var_out = vb.data();
        kernels.row(r);
      }
    });
    std::swap(a, b);
    std::swap(va, vb);
  }
  if (taps) {
    uint64_t filtered = 0;
    for (float f : guide.f) filtered += f != 0.0f;
    *taps = filtered * 25u * uint64_t(p.iterations);
  }
  return a;
}

}  // namespace shadowlab
