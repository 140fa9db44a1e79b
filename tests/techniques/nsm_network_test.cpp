// The NSM network's forward pass (techniques/nsm/nsm_network.h) and its convolution rows
// (techniques/nsm/nsm_conv.h): every instruction set's table gives the scalar table's bytes;
// 1, 2 and 7 threads give the same bytes; each pass matches an independent loop in double
// within the rounding bound of spec §6 (|ŷ − y| ≤ γ_n Σ|w||x| per conv, γ_n = n·u/(1 − n·u),
// u = 2^−24). The network against PyTorch: tools/nsm/test_torch_match.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "core/isa.h"
#include "core/parallel.h"
#include "techniques/nsm/nsm_conv.h"
#include "techniques/nsm/nsm_network.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

constexpr double kU = 1.0 / 16777216.0;  // 2^−24
double gamma_n(double n) { return n * kU / (1 - n * kU); }

NsmWeights random_weights(const NsmArch& a, uint32_t seed) {
  std::mt19937 rng(seed);
  NsmWeights w;
  w.arch = a;
  for (int i = 0; i < a.features; ++i) {
    w.features.push_back("f" + std::to_string(i));
    w.mean.push_back(0.3f * i - 0.2f);
    w.std.push_back(0.5f + 0.4f * i);
  }
  w.convs = nsm_conv_list(a);
  for (NsmConv& c : w.convs) {
    const float bound = 1.3f / std::sqrt(float(c.ic * c.k * c.k));
    std::uniform_real_distribution<float> u(-bound, bound);
    c.weight.resize(size_t(c.oc) * c.ic * c.k * c.k);
    c.bias.resize(size_t(c.oc));
    for (float& v : c.weight) v = u(rng);
    for (float& v : c.bias) v = 0.2f * u(rng);
  }
  return w;
}

std::vector<float> random_planes(int F, int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 1.5f);
  std::vector<float> p(size_t(F) * w * h);
  for (float& v : p) v = n(rng);
  return p;
}

NsmArch arch(const char* name) {
  NsmArch a;
  EXPECT_TRUE(nsm_named_arch(name, a));
  return a;
}

// A tensor of random values (some negative, some exactly zero) in its interior.
NsmTensor random_tensor(int w, int h, int c, uint32_t seed) {
  NsmTensor t;
  t.reset(w, h, c);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w * c; ++x) {
      const float v = u(rng);
      t.px(y, 0)[x] = v < -0.8f ? 0.0f : v;
    }
  return t;
}

double at(const NsmTensor& t, int y, int x, int c) {
  if (y < 0 || y >= t.h || x < 0 || x >= t.w) return 0.0;  // zero padding
  return t.px(y, x)[c];
}

// Conv3 → ReLU → conv1 → ReLU in double from the unpacked weights, with the bound of the fp32
// result: e3 = γ_{9·ic+1} Σ|w||x| + |b|·0 (bias first, exact) per 3×3 output; the 1×1 output's
// bound is Σ|w1|·e3 + γ_{ic+1} Σ|w1||x3|. Returns value and bound per output.
struct Ref {
  std::vector<double> v, bound;  // [y][x][c]
};
Ref ref_pair(const NsmTensor& in, const NsmConv& c3, const NsmConv& c1) {
  const int W = in.w, H = in.h;
  std::vector<double> x3(size_t(W) * H * c3.oc), e3(x3.size());
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int o = 0; o < c3.oc; ++o) {
        double s = c3.bias[size_t(o)], m = std::fabs(c3.bias[size_t(o)]);
        for (int i = 0; i < c3.ic; ++i)
          for (int ky = 0; ky < 3; ++ky)
            for (int kx = 0; kx < 3; ++kx) {
              const double w = c3.weight[((size_t(o) * c3.ic + i) * 3 + ky) * 3 + kx];
              const double v = at(in, y + ky - 1, x + kx - 1, i);
              s += w * v;
              m += std::fabs(w * v);
            }
        const size_t k = (size_t(y) * W + x) * c3.oc + o;
        x3[k] = s > 0 ? s : 0;
        e3[k] = gamma_n(9.0 * c3.ic + 1) * m;
      }
  Ref r;
  r.v.resize(size_t(W) * H * c1.oc);
  r.bound.resize(r.v.size());
  for (size_t p = 0; p < size_t(W) * H; ++p)
    for (int o = 0; o < c1.oc; ++o) {
      double s = c1.bias[size_t(o)], m = std::fabs(c1.bias[size_t(o)]), e = 0;
      for (int i = 0; i < c1.ic; ++i) {
        const double w = c1.weight[size_t(o) * c1.ic + i];
        s += w * x3[p * c3.oc + i];
        m += std::fabs(w) * (std::fabs(x3[p * c3.oc + i]) + e3[p * c3.oc + i]);
        e += std::fabs(w) * e3[p * c3.oc + i];
      }
      r.v[p * c1.oc + o] = s > 0 ? s : 0;
      r.bound[p * c1.oc + o] = e + gamma_n(c1.ic + 1.0) * m;
    }
  return r;
}

NsmPackedConv packed(const NsmConv& c) {
  return {c.oc, c.ic, c.k, nsm_pack_conv_weight(c.weight, c.oc, c.ic, c.k),
          nsm_pack_conv_bias(c.bias, c.oc)};
}

NsmConv random_conv(int oc, int ic, int k, uint32_t seed) {
  NsmConv c;
  c.oc = oc;
  c.ic = ic;
  c.k = k;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  c.weight.resize(size_t(oc) * ic * k * k);
  c.bias.resize(size_t(oc));
  for (float& v : c.weight) v = u(rng);
  for (float& v : c.bias) v = u(rng);
  return c;
}

TEST(NsmConvKernels, EveryTableGivesTheScalarBytes) {
  // Widths over and under every tile (6, 8, 12, 14 pixels), channel counts with block tails.
  for (const int k : {1, 3})
    for (const int cin : {1, 4, 5, 17})
      for (const int cout : {1, 4, 16, 20, 33, 64, 70})
        for (const int width : {1, 5, 13, 31}) {
          const NsmConv c = random_conv(cout, cin, k, uint32_t(cin * 131 + cout * 7 + width));
          const NsmPackedConv p = packed(c);
          const NsmTensor in = random_tensor(width, 3, cin, uint32_t(width + cin));
          for (const bool relu : {false, true}) {
            std::vector<float> want(size_t(width) * cout, -7.0f);
            NsmConvRowArgs a{};
            a.k = k;
            if (k == 3)
              for (int i = 0; i < 3; ++i) a.rows[i] = in.px(i, -1);
            else
              a.rows[0] = in.px(1, 0);
            a.width = width;
            a.cin = cin;
            a.cout = cout;
            a.weight = p.weight.data();
            a.bias = p.bias.data();
            a.out = want.data();
            a.relu = relu;
            nsm_conv_kernels(Isa::scalar).row(a);
            for (const Isa isa : cpu_isas()) {
              std::vector<float> got(want.size(), -9.0f);
              a.out = got.data();
              nsm_conv_kernels(isa).row(a);
              ASSERT_EQ(std::memcmp(got.data(), want.data(), got.size() * 4), 0)
                  << isa_name(isa) << " k " << k << " cin " << cin << " cout " << cout
                  << " width " << width << " relu " << relu;
            }
          }
        }
}

TEST(NsmNetwork, ConvPairAndPoolMatchDoubleWithinTheRoundingBound) {
  // 3×3 with zero padding at every edge (9 × 6 pixels), ReLU, 1×1, ReLU, then the 2×2 pool.
  const NsmConv c3 = random_conv(20, 5, 3, 11), c1 = random_conv(17, 20, 1, 12);
  const NsmTensor in = random_tensor(10, 6, 5, 13);
  NsmTensor out, pooled;
  nsm_conv_pair(in, packed(c3), packed(c1), &out, &pooled);
  const Ref r = ref_pair(in, c3, c1);
  double worst = 0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 10; ++x)
      for (int o = 0; o < 17; ++o) {
        const size_t k = (size_t(y) * 10 + x) * 17 + o;
        const double err = std::fabs(out.px(y, x)[o] - r.v[k]);
        ASSERT_LE(err, r.bound[k]) << y << " " << x << " " << o;
        worst = test::worst_of(worst, err / r.bound[k]);
      }
  // The pool: the mean of the 4 values; its fp32 rounding adds γ_3 of their mean magnitude.
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int o = 0; o < 17; ++o) {
        double s = 0, b = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const size_t k = (size_t(2 * y + dy) * 10 + 2 * x + dx) * 17 + o;
            s += r.v[k] / 4;
            b += r.bound[k] / 4 + gamma_n(3) * std::fabs(r.v[k]) / 4;
          }
        ASSERT_LE(std::fabs(pooled.px(y, x)[o] - s), b) << y << " " << x << " " << o;
      }
  std::printf("conv pair: worst error / bound %.3f\n", worst);
  // The pooled pass without the full-resolution output gives the same bytes.
  NsmTensor pooled_only;
  nsm_conv_pair(in, packed(c3), packed(c1), nullptr, &pooled_only);
  EXPECT_EQ(pooled_only.data, pooled.data);
}

TEST(NsmNetwork, UpsampleAddMatchesTorchsBilinearFormulaAtEveryEdge) {
  // F.interpolate(scale 2, bilinear, align_corners=False): source = (X + 0.5)/2 − 0.5, clamped
  // at 0; i0 = floor, i1 = min(i0 + 1, n − 1), λ = source − i0. 3 × 2 coarse pixels: every
  // output is next to an edge.
  for (const bool with_skip : {false, true}) {
    const NsmTensor u = random_tensor(3, 2, 5, 21), skip = random_tensor(6, 4, 5, 22);
    NsmTensor out;
    nsm_upsample_add(u, with_skip ? &skip : nullptr, out);
    ASSERT_EQ(out.w, 6);
    ASSERT_EQ(out.h, 4);
    auto src = [](int X, int n, int& i0, int& i1, double& l) {
      const double s = std::max(0.0, (X + 0.5) / 2 - 0.5);
      i0 = int(std::floor(s));
      i1 = std::min(i0 + 1, n - 1);
      l = s - i0;
    };
    for (int Y = 0; Y < 4; ++Y)
      for (int X = 0; X < 6; ++X)
        for (int c = 0; c < 5; ++c) {
          int y0, y1, x0, x1;
          double ly, lx;
          src(Y, 2, y0, y1, ly);
          src(X, 3, x0, x1, lx);
          double v = (1 - ly) * ((1 - lx) * at(u, y0, x0, c) + lx * at(u, y0, x1, c)) +
                     ly * ((1 - lx) * at(u, y1, x0, c) + lx * at(u, y1, x1, c));
          double m = 0;
          for (int yy : {y0, y1})
            for (int xx : {x0, x1}) m = std::max(m, std::fabs(at(u, yy, xx, c)));
          double bound = gamma_n(4) * m;  // two rounded blends of weights 3/4 and 1/4
          if (with_skip) {
            v += at(skip, Y, X, c);
            bound += kU * (m + std::fabs(at(skip, Y, X, c))) * 1.01;
          }
          ASSERT_LE(std::fabs(out.px(Y, X)[c] - v), bound) << Y << " " << X << " " << c;
        }
  }
}

TEST(NsmNetwork, FusedDecoderEqualsUpsampleThenConvPair) {
  const NsmConv c3 = random_conv(6, 5, 3, 31), c1 = random_conv(7, 6, 1, 32);
  const NsmTensor u = random_tensor(5, 9, 5, 33), skip = random_tensor(10, 18, 5, 34);
  NsmTensor fused, up, unfused;
  nsm_decoder_level(u, &skip, packed(c3), packed(c1), fused);
  nsm_upsample_add(u, &skip, up);
  nsm_conv_pair(up, packed(c3), packed(c1), &unfused, nullptr);
  EXPECT_EQ(fused.data, unfused.data);
}

TEST(NsmNetwork, InputIsStandardizedAndEdgeReplicated) {
  const NsmWeights w = random_weights(arch("tiny"), 1);
  const NsmNetwork net = nsm_network(w);
  const std::vector<float> planes = random_planes(4, 5, 3, 2);
  NsmTensor x;
  nsm_input(net, planes.data(), 5, 3, 8, 4, x);
  for (int y = 0; y < 4; ++y)
    for (int xx = 0; xx < 8; ++xx)
      for (int i = 0; i < 4; ++i) {
        const float f = planes[(size_t(i) * 3 + std::min(y, 2)) * 5 + std::min(xx, 4)];
        EXPECT_EQ(x.px(y, xx)[i], (f - w.mean[size_t(i)]) / w.std[size_t(i)]);
      }
}

TEST(NsmNetwork, EveryInstructionSetAndThreadCountGivesTheSameBytes) {
  // nsm3 at 37 × 29 (padded to 40 × 32): every level's band split has a short last band.
  const NsmNetwork net = nsm_network(random_weights(arch("nsm3"), 3));
  const int W = 37, H = 29;
  const std::vector<float> planes = random_planes(4, W, H, 4);
  std::vector<float> want(size_t(W) * H);
  const int threads = thread_count();
  {
    ScopedIsa scalar(Isa::scalar);
    set_thread_count(1);
    nsm_forward(net, planes.data(), W, H, want.data());
  }
  for (const Isa isa : cpu_isas())
    for (const int n : {1, 2, 7}) {
      ScopedIsa use(isa);
      set_thread_count(n);
      std::vector<float> got(want.size(), -1.0f);
      nsm_forward(net, planes.data(), W, H, got.data());
      EXPECT_EQ(std::memcmp(got.data(), want.data(), got.size() * 4), 0)
          << isa_name(isa) << " at " << n << " threads";
    }
  set_thread_count(threads);
  for (const float v : want) {
    EXPECT_GT(v, 0.0f);
    EXPECT_LT(v, 1.0f);
  }
}

TEST(NsmNetwork, SixteenBitStorageStaysNearFp32) {
  const NsmNetwork net = nsm_network(random_weights(arch("tiny"), 5));
  const int W = 24, H = 20;
  const std::vector<float> planes = random_planes(4, W, H, 6);
  std::vector<float> f32(size_t(W) * H), low(f32.size());
  nsm_forward(net, planes.data(), W, H, f32.data());
  for (const NsmPrecision p : {NsmPrecision::f16, NsmPrecision::bf16}) {
    nsm_forward(net, planes.data(), W, H, low.data(), p);
    double worst = 0;
    for (size_t i = 0; i < f32.size(); ++i) worst = test::worst_of(worst, double(std::fabs(low[i] - f32[i])));
    std::printf("%s storage: max |output − fp32 output| %.3g\n", nsm_precision_name(p), worst);
    // Relative storage rounding 2^−11 (f16) or 2^−8 (bf16) per stored tensor, through ~6 stored
    // tensors and a sigmoid of slope ≤ 1/4, on activations of order 1: far below these.
    EXPECT_GT(worst, 0.0);
    EXPECT_LT(worst, p == NsmPrecision::f16 ? 5e-3 : 4e-2);
  }
  EXPECT_EQ(nsm_round_storage(1.0f + std::ldexp(1.0f, -11), NsmPrecision::f16), 1.0f);  // tie → even
  EXPECT_EQ(nsm_round_storage(1.0f + 3 * std::ldexp(1.0f, -11), NsmPrecision::f16),
            1.0f + std::ldexp(1.0f, -9));
  // binary16's ends: the largest finite value, overflow, ties in the subnormal range.
  EXPECT_EQ(nsm_round_storage(65519.0f, NsmPrecision::f16), 65504.0f);
  EXPECT_TRUE(std::isinf(nsm_round_storage(-65520.0f, NsmPrecision::f16)));
  EXPECT_EQ(nsm_round_storage(std::ldexp(1.0f, -25), NsmPrecision::f16), 0.0f);
  EXPECT_EQ(nsm_round_storage(3 * std::ldexp(1.0f, -25), NsmPrecision::f16), std::ldexp(1.0f, -23));
  EXPECT_EQ(nsm_round_storage(std::ldexp(1.0f, -14) * 1.0003f, NsmPrecision::f16), std::ldexp(1.0f, -14));
  EXPECT_EQ(nsm_round_storage(1.0f + std::ldexp(1.0f, -8), NsmPrecision::bf16), 1.0f);
  EXPECT_EQ(nsm_round_storage(1.0f + 3 * std::ldexp(1.0f, -8), NsmPrecision::bf16),
            1.0f + std::ldexp(1.0f, -6));
}

}  // namespace
}  // namespace shadowlab
