#include "techniques/nsm/nsm_network.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstring>

#include "core/error.h"
#include "core/isa.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "techniques/nsm/nsm_conv.h"

namespace shadowlab {

namespace {

// Row bands of every pass: 8 rows (4 row pairs in the encoder), fixed, so the bands and each
// output's arithmetic do not depend on the thread count.
constexpr size_t kNsmBandRows = 8;

// Per-thread scratch rows, grown as needed (never shrunk): a band's 3×3 output row, the
// decoder's input rows, the head's rows.
struct NsmScratch {
  std::vector<float> a, b, c, d;
};
NsmScratch& nsm_scratch() {
  thread_local NsmScratch s;
  return s;
}
float* nsm_grow(std::vector<float>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return v.data();
}

NsmConvRowArgs nsm_args(const NsmPackedConv& c, int width, float* out, bool relu) {
  NsmConvRowArgs a{};
  a.k = c.k;
  a.width = width;
  a.cin = c.ic;
  a.cout = c.oc;
  a.weight = c.weight.data();
  a.bias = c.bias.data();
  a.out = out;
  a.relu = relu;
  return a;
}

// One output row y of conv3 → ReLU → conv1 → ReLU from the padded input `in` (rows[ky] at the
// padded row y + ky, x = −1), into dst (w × conv1.oc values).
void nsm_pair_row(const NsmConvKernels& k, const float* const rows[3], int width,
                  const NsmPackedConv& conv3, const NsmPackedConv& conv1, float* mid, float* dst) {
  NsmConvRowArgs a = nsm_args(conv3, width, mid, true);
  for (int i = 0; i < 3; ++i) a.rows[i] = rows[i];
  k.row(a);
  NsmConvRowArgs b = nsm_args(conv1, width, dst, true);
  b.rows[0] = mid;
  k.row(b);
}

// Row Y of up(coarse) (+ skip row) into dst (2·coarse.w pixels × C). tmp: coarse.w × C.
void nsm_up_row(const NsmTensor& u, int Y, const float* skip, float* dst, float* tmp) {
  const int C = u.c, cw = u.w, k = Y / 2;
  const int n = (Y % 2 == 0) ? k - 1 : k + 1;
  const float* A = u.px(k, 0);
  const size_t rowlen = size_t(cw) * C;
  if (n < 0 || n >= u.h) {
    std::memcpy(tmp, A, rowlen * sizeof(float));
  } else {
    const float* B = u.px(n, 0);
    for (size_t i = 0; i < rowlen; ++i) tmp[i] = 0.75f * A[i] + 0.25f * B[i];
  }
  for (int X = 0; X < 2 * cw; ++X) {
    const int kx = X / 2, nx = (X % 2 == 0) ? kx - 1 : kx + 1;
    const float* p = tmp + size_t(kx) * C;
    float* o = dst + size_t(X) * C;
    if (nx < 0 || nx >= cw) {
      for (int c = 0; c < C; ++c) o[c] = p[c];
    } else {
      const float* q = tmp + size_t(nx) * C;
      for (int c = 0; c < C; ++c) o[c] = 0.75f * p[c] + 0.25f * q[c];
    }
    if (skip) {
      const float* s = skip + size_t(X) * C;
      for (int c = 0; c < C; ++c) o[c] = o[c] + s[c];
    }
  }
}

void nsm_quantize(NsmTensor& t, NsmPrecision p) {
  if (p == NsmPrecision::f32) return;
  parallel_for_chunks(t.data.size(), size_t(1) << 16, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) t.data[i] = nsm_round_storage(t.data[i], p);
  });
}

float nsm_sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }

}  // namespace

const char* nsm_precision_name(NsmPrecision p) {
  switch (p) {
    case NsmPrecision::f16: return "f16";
    case NsmPrecision::bf16: return "bf16";
    default: return "f32";
  }
}

float nsm_round_storage(float v, NsmPrecision p) {
  if (p == NsmPrecision::f16) {
    // binary16 keeps 11 significant bits down to 2^−14 and a fixed quantum 2^−24 below it;
    // nearbyint rounds to nearest even (the default mode), and the scalings are exact.
    if (!std::isfinite(v)) return v;
    const float a = std::fabs(v);
    if (a >= 65520.0f) return std::copysign(INFINITY, v);  // past 65504 + half its quantum
    int e = 0;
    std::frexp(a, &e);  // a = m · 2^e, m in [0.5, 1)
    const float q = std::ldexp(1.0f, std::max(e - 11, -24));
    return std::copysign(std::nearbyint(a / q) * q, v);
  }
  if (p == NsmPrecision::bf16) {
    if (std::isnan(v)) return v;
    uint32_t b;
    std::memcpy(&b, &v, 4);
    b = (b + 0x7FFFu + ((b >> 16) & 1u)) & 0xFFFF0000u;  // round to nearest even
    float r;
    std::memcpy(&r, &b, 4);
    return r;
  }
  return v;
}

void NsmTensor::reset(int width, int height, int channels) {
  w = width;
  h = height;
  c = channels;
  data.assign((size_t(h) + 2) * (size_t(w) + 2) * size_t(c), 0.0f);
}

NsmNetwork nsm_network(const NsmWeights& w) {
  NsmNetwork n;
  n.arch = w.arch;
  n.mean = w.mean;
  n.std = w.std;
  for (const NsmConv& c : w.convs) {
    NsmPackedConv p;
    p.oc = c.oc;
    p.ic = c.ic;
    p.k = c.k;
    p.weight = nsm_pack_conv_weight(c.weight, c.oc, c.ic, c.k);
    p.bias = nsm_pack_conv_bias(c.bias, c.oc);
    n.convs.push_back(std::move(p));
  }
  return n;
}

void nsm_input(const NsmNetwork& net, const float* planes, int width, int height, int pw, int ph,
               NsmTensor& x) {
  const int F = net.arch.features;
  x.reset(pw, ph, F);
  parallel_for_chunks(size_t(ph), kNsmBandRows, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y) {
      const size_t sy = std::min(y, size_t(height) - 1);
      float* row = x.px(int(y), 0);
      for (int xx = 0; xx < pw; ++xx) {
        const size_t sx = size_t(std::min(xx, width - 1));
        for (int i = 0; i < F; ++i)
          row[size_t(xx) * F + i] =
              (planes[(size_t(i) * height + sy) * width + sx] - net.mean[size_t(i)]) /
              net.std[size_t(i)];
      }
    }
  });
}

void nsm_conv_pair(const NsmTensor& in, const NsmPackedConv& conv3, const NsmPackedConv& conv1,
                   NsmTensor* out, NsmTensor* pooled) {
  const NsmConvKernels& k = nsm_conv_kernels(process_isa());
  const int W = in.w, H = in.h, C = conv1.oc;
  if (out) out->reset(W, H, C);
  if (pooled) pooled->reset(W / 2, H / 2, C);
  const size_t rows_per_step = pooled ? 2 : 1;
  const size_t steps = pooled ? size_t(H / 2) : size_t(H);
  parallel_for_chunks(steps, kNsmBandRows / rows_per_step, [&](size_t s0, size_t s1) {
    NsmScratch& sc = nsm_scratch();
    float* mid = nsm_grow(sc.a, size_t(W) * conv3.oc);
    float* pair = nsm_grow(sc.b, 2 * size_t(W) * C);
    for (size_t s = s0; s < s1; ++s) {
      float* got[2] = {nullptr, nullptr};
      for (size_t j = 0; j < rows_per_step; ++j) {
        const int y = int(s * rows_per_step + j);
        const float* rows[3] = {in.px(y - 1, -1), in.px(y, -1), in.px(y + 1, -1)};
        got[j] = out ? out->px(y, 0) : pair + j * size_t(W) * C;
        nsm_pair_row(k, rows, W, conv3, conv1, mid, got[j]);
      }
      if (pooled) {
        float* o = pooled->px(int(s), 0);
        for (int x = 0; x < W / 2; ++x)
          for (int c = 0; c < C; ++c) {
            const size_t a = size_t(2 * x) * C + c, b = a + C;
            o[size_t(x) * C + c] = ((got[0][a] + got[0][b]) + (got[1][a] + got[1][b])) * 0.25f;
          }
      }
    }
  });
}

void nsm_upsample_add(const NsmTensor& coarse, const NsmTensor* skip, NsmTensor& out) {
  out.reset(2 * coarse.w, 2 * coarse.h, coarse.c);
  parallel_for_chunks(size_t(out.h), kNsmBandRows, [&](size_t y0, size_t y1) {
    float* tmp = nsm_grow(nsm_scratch().a, size_t(coarse.w) * coarse.c);
    for (size_t y = y0; y < y1; ++y)
      nsm_up_row(coarse, int(y), skip ? skip->px(int(y), 0) : nullptr, out.px(int(y), 0), tmp);
  });
}

namespace {

// The decoder's band loop: rows [y0, y1) of up(coarse) (+ skip) → conv3 → ReLU → conv1 → ReLU,
// each row handed to emit(y, row) (W × conv1.oc values, in scratch `dst`).
template <class Emit>
void nsm_decoder_band(const NsmConvKernels& k, const NsmTensor& coarse, const NsmTensor* skip,
                      const NsmPackedConv& conv3, const NsmPackedConv& conv1, size_t y0,
                      size_t y1, Emit&& emit) {
  const int W = 2 * coarse.w, H = 2 * coarse.h, C = coarse.c;
  NsmScratch& sc = nsm_scratch();
  const size_t padded_row = (size_t(W) + 2) * C;
  const size_t band = y1 - y0 + 2;
  float* in = nsm_grow(sc.a, band * padded_row);
  float* tmp = nsm_grow(sc.b, size_t(coarse.w) * C);
  float* mid = nsm_grow(sc.c, size_t(W) * conv3.oc);
  float* dst = nsm_grow(sc.d, size_t(W) * conv1.oc);
  for (size_t r = 0; r < band; ++r) {
    float* row = in + r * padded_row;
    const long y = long(y0) + long(r) - 1;
    std::fill(row, row + C, 0.0f);
    std::fill(row + padded_row - C, row + padded_row, 0.0f);
    if (y < 0 || y >= H)
      std::fill(row, row + padded_row, 0.0f);
    else
      nsm_up_row(coarse, int(y), skip ? skip->px(int(y), 0) : nullptr, row + C, tmp);
  }
  for (size_t y = y0; y < y1; ++y) {
    const size_t r = y - y0;
    const float* rows[3] = {in + r * padded_row, in + (r + 1) * padded_row,
                            in + (r + 2) * padded_row};
    nsm_pair_row(k, rows, W, conv3, conv1, mid, dst);
    emit(y, static_cast<const float*>(dst));
  }
}

}  // namespace

void nsm_decoder_level(const NsmTensor& coarse, const NsmTensor* skip, const NsmPackedConv& conv3,
                       const NsmPackedConv& conv1, NsmTensor& out) {
  const NsmConvKernels& k = nsm_conv_kernels(process_isa());
  out.reset(2 * coarse.w, 2 * coarse.h, conv1.oc);
  const size_t rowlen = size_t(out.w) * out.c;
  parallel_for_chunks(size_t(out.h), kNsmBandRows, [&](size_t y0, size_t y1) {
    nsm_decoder_band(k, coarse, skip, conv3, conv1, y0, y1, [&](size_t y, const float* row) {
      std::memcpy(out.px(int(y), 0), row, rowlen * sizeof(float));
    });
  });
}

void nsm_forward(const NsmNetwork& net, const float* planes, int width, int height, float* out,
                 NsmPrecision precision, NsmForwardStats* stats, const NsmTensorSink& sink) {
  const NsmArch& a = net.arch;
  SL_CHECK(width > 0 && height > 0);
  const int L = a.levels, m = 1 << (L - 1);
  const int pw = (width + m - 1) / m * m, ph = (height + m - 1) / m * m;
  uint64_t bytes = 0;
  auto tensor_bytes = [](const NsmTensor& t) { return uint64_t(t.w) * t.h * t.c * 4; };
  auto stored = [&](NsmTensor& t, const std::string& name) {
    nsm_quantize(t, precision);
    bytes += tensor_bytes(t);
    if (sink) sink(name, t);
  };
  std::vector<NsmPassStats> passes;
  // Times one pass; its MACs from the convolutions it runs at `pixels` output pixels each.
  auto timed = [&](const std::string& name, int level, std::initializer_list<size_t> convs,
                   double pixels, auto&& run) {
    const uint64_t before = bytes;
    const auto t0 = std::chrono::steady_clock::now();
    NsmPassStats p;
    p.bytes_read = run();
    p.ms = ms_since(t0);
    p.name = name;
    p.level = level;
    for (size_t c : convs) {
      const NsmPackedConv& k = net.convs[c];
      p.macs += double(k.k) * k.k * k.ic * k.oc * pixels;
    }
    p.bytes_written = bytes - before;
    passes.push_back(p);
  };
  auto pixels_at = [&](int level) { return double(pw >> level) * double(ph >> level); };
  NsmTensor x;
  timed("input", 0, {}, 0, [&] {
    nsm_input(net, planes, width, height, pw, ph, x);
    stored(x, "input");
    return uint64_t(width) * height * a.features * 4;
  });
  // Encoder: level 0 keeps no skip (decoder 0 has none); levels 1..L−2 keep e_l.
  std::vector<NsmTensor> skips(size_t(L) - 1);
  size_t ci = 0;
  for (int l = 0; l <= L - 2; ++l) {
    timed("enc" + std::to_string(l), l, {ci, ci + 1}, pixels_at(l), [&] {
      NsmTensor pooled;
      nsm_conv_pair(x, net.convs[ci], net.convs[ci + 1], l == 0 ? nullptr : &skips[size_t(l)],
                    &pooled);
      if (l > 0) stored(skips[size_t(l)], "enc" + std::to_string(l));
      stored(pooled, "pool" + std::to_string(l));
      const uint64_t read = tensor_bytes(x);
      x = std::move(pooled);
      return read;
    });
    ci += 2;
  }
  NsmTensor u;
  timed("mid", L - 1, {ci, ci + 1}, pixels_at(L - 1), [&] {
    nsm_conv_pair(x, net.convs[ci], net.convs[ci + 1], &u, nullptr);
    stored(u, "mid");
    return tensor_bytes(x);
  });
  ci += 2;
  for (int l = L - 2; l >= 1; --l) {
    timed("dec" + std::to_string(l), l, {ci, ci + 1}, pixels_at(l), [&] {
      NsmTensor next;
      nsm_decoder_level(u, &skips[size_t(l)], net.convs[ci], net.convs[ci + 1], next);
      stored(next, "dec" + std::to_string(l));
      const uint64_t read = tensor_bytes(u) + tensor_bytes(skips[size_t(l)]);
      u = std::move(next);
      return read;
    });
    ci += 2;
  }
  // Decoder 0 and the head, cropped to width × height.
  const NsmConvKernels& k = nsm_conv_kernels(process_isa());
  const NsmPackedConv &c3 = net.convs[ci], &c1 = net.convs[ci + 1], &head = net.convs[ci + 2];
  timed("dec0+head", 0, {ci, ci + 1, ci + 2}, pixels_at(0), [&] {
    parallel_for_chunks(size_t(height), kNsmBandRows, [&](size_t y0, size_t y1) {
      nsm_decoder_band(k, u, nullptr, c3, c1, y0, y1, [&](size_t y, const float* row) {
        thread_local std::vector<float> logits;
        float* lg = nsm_grow(logits, size_t(pw));
        NsmConvRowArgs b = nsm_args(head, width, lg, false);
        b.rows[0] = row;
        k.row(b);
        float* o = out + y * size_t(width);
        for (int xx = 0; xx < width; ++xx) o[xx] = nsm_sigmoid(lg[xx]);
      });
    });
    bytes += uint64_t(width) * height * 4;
    return tensor_bytes(u);
  });
  if (stats) {
    stats->padded_width = pw;
    stats->padded_height = ph;
    stats->macs = nsm_macs_per_pixel(a) * pw * ph;
    stats->activation_bytes = bytes;
    stats->passes = std::move(passes);
  }
}

}  // namespace shadowlab
