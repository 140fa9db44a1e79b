#pragma once
// The Neural Shadow Mapping network's forward pass on the CPU (docs/techniques/nsm.md, "Network
// and inference"): the UNet of NsmArch (techniques/nsm/nsm_weights.h) on F feature planes.
//
//   standardize: x_i = (f_i − mean_i) / std_i (fp32, edge-replicated to a multiple of 2^(L−1))
//   encoder l = 0..L−2: conv3×3 → ReLU → conv1×1 → ReLU = e_l; avg_pool 2×2 → next level
//   bottleneck:         conv3×3 (→ B) → ReLU → conv1×1 (→ C_{L−2}) → ReLU = u
//   decoder l = L−2..1: up(u) + e_l → conv3×3 → ReLU → conv1×1 → ReLU = u
//   decoder 0:          up(u) → conv3×3 → ReLU → conv1×1 (→ head) → ReLU → conv1×1 (→ 1)
//                       → sigmoid, cropped to the input's size
// conv3×3 pads with zeros; up is bilinear ×2 with align_corners=False (output row 2k + 1/2 maps
// to input row k + 1/4: 3/4 of row k and 1/4 of row k ± 1, the edge rows clamped); the pool is
// ((a + b) + (c + d)) · 0.25.
//
// Activations are channels-last rows [y][x][C] with a one-pixel zero border. Each level is one
// pass over fixed row bands (core/parallel.h; band sizes depend on the problem only) that fuses
// the 1×1 after the 3×3 row by row; the encoder pools in the same pass, the decoder builds its
// 3×3 input rows (up + skip) per band, recomputing a one-row halo. Every output has one fixed
// summation order (techniques/nsm/nsm_conv.h), so the result does not depend on the thread count
// or the instruction set.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "techniques/nsm/nsm_weights.h"

namespace shadowlab {

// How the activations that reach memory (the input, skips, pooled and decoder outputs) are
// stored: fp32, or rounded to fp16 / bf16 (round to nearest even) after each is computed.
// Arithmetic is fp32 throughout. The rounded forms are stored in fp32 slots here: they measure
// the precision a 16-bit store would have, not its bandwidth.
enum class NsmPrecision { f32, f16, bf16 };
const char* nsm_precision_name(NsmPrecision p);
float nsm_round_storage(float v, NsmPrecision p);

// A conv with its packed weights (nsm_conv.h).
struct NsmPackedConv {
  int oc = 0, ic = 0, k = 0;
  std::vector<float> weight, bias;
};

struct NsmNetwork {
  NsmArch arch;
  std::vector<float> mean, std;
  std::vector<NsmPackedConv> convs;  // nsm_conv_list's order
};
NsmNetwork nsm_network(const NsmWeights& w);

// An activation tensor: h × w pixels of c channels, channels-last, with a one-pixel zero border
// (pixel (y, x) at data[((y + 1)(w + 2) + x + 1)·c]).
struct NsmTensor {
  int w = 0, h = 0, c = 0;
  std::vector<float> data;
  void reset(int width, int height, int channels);  // zeros
  float* px(int y, int x) { return data.data() + ((size_t(y) + 1) * (w + 2) + x + 1) * c; }
  const float* px(int y, int x) const {
    return data.data() + ((size_t(y) + 1) * (w + 2) + x + 1) * c;
  }
};

// One pass of the forward: "input", "enc<l>" (level l's conv pair and its pool), "mid",
// "dec<l>" (l ≥ 1), "dec0+head". Bytes at 4 a value: what it reads of stored tensors and what
// it stores.
struct NsmPassStats {
  std::string name;
  int level = 0;
  double ms = 0;
  double macs = 0;
  uint64_t bytes_read = 0, bytes_written = 0;
};

struct NsmForwardStats {
  int padded_width = 0, padded_height = 0;
  double macs = 0;                // multiply-adds of the convolutions
  uint64_t activation_bytes = 0;  // the tensors that reach memory, at 4 bytes a value
  std::vector<NsmPassStats> passes;  // in execution order; their ms are wall times
};

// Receives every tensor that reaches memory, as stored, under its name: "input", "enc<l>" (the
// skip e_l, l ≥ 1), "pool<l>" (the pooled e_l), "mid" (the bottleneck's u), "dec<l>" (l ≥ 1).
using NsmTensorSink = std::function<void(const std::string& name, const NsmTensor& t)>;

// The forward pass: `planes` holds F = net.arch.features planes of width × height fp32 values,
// plane after plane, row-major; `out` receives width × height values in (0, 1).
void nsm_forward(const NsmNetwork& net, const float* planes, int width, int height, float* out,
                 NsmPrecision precision = NsmPrecision::f32, NsmForwardStats* stats = nullptr,
                 const NsmTensorSink& sink = nullptr);

// The passes nsm_forward is made of, for the tests.
// Standardized, edge-replicated input of pw × ph (pw ≥ width, ph ≥ height).
void nsm_input(const NsmNetwork& net, const float* planes, int width, int height, int pw, int ph,
               NsmTensor& x);
// conv3 → ReLU → conv1 → ReLU; with pooled: also the 2×2 average of the result (even sizes),
// and `out` may then be null (the result is not kept).
void nsm_conv_pair(const NsmTensor& in, const NsmPackedConv& conv3, const NsmPackedConv& conv1,
                   NsmTensor* out, NsmTensor* pooled);
// up(coarse) (+ skip when given) → conv3 → ReLU → conv1 → ReLU, at twice coarse's size.
void nsm_decoder_level(const NsmTensor& coarse, const NsmTensor* skip, const NsmPackedConv& conv3,
                       const NsmPackedConv& conv1, NsmTensor& out);
// up(coarse) (+ skip when given) alone (the decoder's input, materialized).
void nsm_upsample_add(const NsmTensor& coarse, const NsmTensor* skip, NsmTensor& out);

}  // namespace shadowlab
