#pragma once
// The convolution rows of the NSM network (techniques/nsm/nsm_network.h): one output row of a
// 3×3 (zero-padded) or 1×1 convolution over channels-last activations, bias on, ReLU optional.
//
// Every output value is one fixed chain of fused multiply-adds: acc = bias, then for ic
// ascending, ky = 0..2, kx = 0..2: acc = fma(w[oc][ic][ky][kx], x[ic][y+ky−1][x+kx−1], acc);
// then max(acc, 0) when relu (acc > 0 ? acc : +0, so −0 and NaN give +0). The scalar table is
// the oracle and calls std::fma (one rounding, as the hardware instruction); the AVX2 and AVX-512
// rows (nsm_conv_avx2.cpp, nsm_conv_avx512.cpp) run the same chain per lane with vfmadd, so the
// three give the same bits (tests/techniques/nsm_network_test.cpp). These are the only ISA
// objects allowed to hold FMA instructions (tests/check_isa_objects.sh, docs/simd.md).
#include <vector>

#include "core/isa.h"

namespace shadowlab {

// Output channels are packed in blocks of kNsmOcBlock: weight [block][ic][tap][16] with the
// lanes past oc zero, bias [block·16].
constexpr int kNsmOcBlock = 16;

struct NsmConvRowArgs {
  // k = 3: rows[ky] is input row y + ky − 1 starting one zero pixel left of x = 0 (pixel x's
  // window starts at rows[ky] + x·cin; one zero pixel right of x = width − 1 too). k = 1:
  // rows[0] is the row itself, pixel x at rows[0] + x·cin.
  const float* rows[3];
  int k;
  int width;
  int cin, cout;
  const float* weight;  // nsm_pack_conv_weight's layout
  const float* bias;    // nsm_pack_conv_bias's layout
  float* out;           // pixel x's cout values at out + x·cout
  bool relu;
};
using NsmConvRowFn = void (*)(const NsmConvRowArgs& a);

struct NsmConvKernels {
  Isa isa;  // the instruction set the row was compiled for
  NsmConvRowFn row;
};
const NsmConvKernels& nsm_conv_kernels(Isa isa);

// The packed layouts of a weight [oc][ic][k][k] and a bias [oc].
std::vector<float> nsm_pack_conv_weight(const std::vector<float>& w, int oc, int ic, int k);
std::vector<float> nsm_pack_conv_bias(const std::vector<float>& b, int oc);

}  // namespace shadowlab
