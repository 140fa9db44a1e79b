#include "techniques/nsm/nsm_conv.h"

#include <cmath>

namespace shadowlab {

#if defined(__x86_64__)
// The vector rows (techniques/nsm/nsm_conv_avx2.cpp, nsm_conv_avx512.cpp).
namespace nsm_conv_avx2 {
void row(const NsmConvRowArgs& a);
}
namespace nsm_conv_avx512 {
void row(const NsmConvRowArgs& a);
}
#endif

namespace {

// The oracle: each output's chain of std::fma in the order of nsm_conv.h.
void nsm_conv_row_scalar(const NsmConvRowArgs& a) {
  const int taps = a.k * a.k;
  for (int x = 0; x < a.width; ++x)
    for (int oc = 0; oc < a.cout; ++oc) {
      const int block = oc / kNsmOcBlock, lane = oc % kNsmOcBlock;
      float acc = a.bias[oc];
      for (int ic = 0; ic < a.cin; ++ic)
        for (int t = 0; t < taps; ++t) {
          const int ky = t / a.k, kx = t % a.k;
          const float w =
              a.weight[((size_t(block) * a.cin + ic) * taps + t) * kNsmOcBlock + lane];
          acc = std::fma(w, a.rows[ky][size_t(x + kx) * a.cin + ic], acc);
        }
      if (a.relu) acc = acc > 0.0f ? acc : 0.0f;
      a.out[size_t(x) * a.cout + oc] = acc;
    }
}

constexpr NsmConvKernels kNsmConvScalar{Isa::scalar, nsm_conv_row_scalar};
#if defined(__x86_64__)
constexpr NsmConvKernels kNsmConvAvx2{Isa::avx2, nsm_conv_avx2::row};
constexpr NsmConvKernels kNsmConvAvx512{Isa::avx512, nsm_conv_avx512::row};
#endif

}  // namespace

const NsmConvKernels& nsm_conv_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa == Isa::avx512) return kNsmConvAvx512;
  if (isa == Isa::avx2) return kNsmConvAvx2;
#endif
  (void)isa;
  return kNsmConvScalar;
}

std::vector<float> nsm_pack_conv_weight(const std::vector<float>& w, int oc, int ic, int k) {
  const int blocks = (oc + kNsmOcBlock - 1) / kNsmOcBlock, taps = k * k;
  std::vector<float> p(size_t(blocks) * ic * taps * kNsmOcBlock, 0.0f);
  for (int o = 0; o < oc; ++o)
    for (int i = 0; i < ic; ++i)
      for (int t = 0; t < taps; ++t)
        p[((size_t(o / kNsmOcBlock) * ic + i) * taps + t) * kNsmOcBlock + o % kNsmOcBlock] =
            w[(size_t(o) * ic + i) * taps + t];
  return p;
}

std::vector<float> nsm_pack_conv_bias(const std::vector<float>& b, int oc) {
  const int blocks = (oc + kNsmOcBlock - 1) / kNsmOcBlock;
  std::vector<float> p(size_t(blocks) * kNsmOcBlock, 0.0f);
  for (int o = 0; o < oc; ++o) p[size_t(o)] = b[size_t(o)];
  return p;
}

}  // namespace shadowlab
