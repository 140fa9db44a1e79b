#pragma once
// Edge-avoiding à-trous filtering of a noisy visibility mask (Dammertz, Sewtz, Hanika and Lensch
// 2010), guided by the GBuffer (docs/techniques/rts.md). Each iteration i = 0..N−1 is a 5×5
// B3-spline kernel (1, 4, 6, 4, 1)/16 per axis whose taps lie 2^i pixels apart, each tap weighted
// by the edge-stopping terms of the GBuffer and of the values:
//   depth   exp(−|z_p − z_q| / (σ_z · g_p · |o| + ε)), z the view depth, g_p the pixel's depth
//           gradient (metres per pixel) and |o| the tap's offset in pixels (the SVGF form: a
//           plane seen at a grazing angle keeps its neighbours, a depth step does not);
//   normal  max(0, n_p · n_q)^(2^k), the geometric normals (k = 7: the power 128 of SVGF);
//   value   exp(−|v_p − v_q| / (σ_v · √var_p + ε)), v the previous iteration's values and var_p
//           their variance (SVGF's variance-guided term): a shadow's edge on a plane, which the
//           GBuffer cannot see, stops the filter where the values differ by more than their
//           noise. The input's variance is the binomial one of an n-sample estimate,
//           m(1 − m)/n, m the mean of the 3 × 3 filtered neighbourhood; each iteration carries
//           it on as Σ w²·var_q / (Σ w)², the variance of its weighted mean;
// and the weights renormalized. Only covered pixels facing the light are filtered, and only they
// are taps: the facing-away pixels are 0 by the mask convention and the uncovered 1, neither
// noise, so neither bleeds into its neighbours.
//
// A kernel family (docs/simd.md): one row of one iteration per call, the scalar table the oracle;
// the AVX2 and AVX-512 rows (one body, techniques/rt/atrous_simd.inl) give its bits.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/math.h"

namespace shadowlab {

// ε of the depth term's denominator (metres): a plane seen face-on has g = 0, where any depth
// difference then stops the filter (SVGF's floor).
constexpr float kAtrousDepthEps = 1e-4f;
// exp_f's domain ends at −87 (core/exp_log.h); e^−87 ≈ 1.6e-38 is a weight of 0 in effect.
constexpr float kAtrousMinExponent = -87.0f;
// ε of the value term's denominator: where the variance is 0 (a neighbourhood all lit or all
// dark), any difference stops the filter.
constexpr float kAtrousValueEps = 1e-4f;

struct AtrousParams {
  int iterations = 4;     // N: taps up to 2·2^(N−1) pixels away (61 × 61 for N = 4)
  float sigma_z = 1.0f;   // depth term's scale
  int normal_power = 7;   // k: the normal term's power is 2^k
  float sigma_v = 1.0f;   // value term's scale, in standard deviations; 0: no value term
  int samples = 1;        // samples per pixel of the input (its variance m(1 − m)/samples)
};

// The GBuffer as the rows read it: planes of W × H floats, zero where f is 0.
struct AtrousGuide {
  int width = 0, height = 0;
  std::vector<float> z, g, nx, ny, nz;
  std::vector<float> f;  // 1: filtered and a tap (covered, facing the light); else 0
};
// The guide of `g` for a light at `light` (facing: n · (L − P) > 0, as the ray tracer decides).
AtrousGuide atrous_guide(const GBuffer& g, vec3 light);

// One row of one iteration: out[y·W + x] for every x.
struct AtrousRow {
  const float* in = nullptr;
  float* out = nullptr;
  const AtrousGuide* guide = nullptr;
  int y = 0;
  int step = 1;             // 2^i
  const float* tap_c = nullptr;  // 25 (row-major dy, dx): σ_z · step · |(dx, dy)|
  int normal_power = 7;
  float sigma_v = 0.0f;     // the value term's σ_v (0: no value term)
  const float* var_in = nullptr;  // the values' variance
  float* var_out = nullptr;
};
using AtrousRowKernel = void (*)(const AtrousRow& row);

struct AtrousKernels {
  Isa isa;
  AtrousRowKernel row;
};
const AtrousKernels& atrous_kernels(Isa isa);

// The filtered mask (a new image; pixels with f = 0 keep their values). `taps`, when given,
// receives the taps evaluated: 25 per filtered pixel per iteration.
ImageF atrous_denoise(const ImageF& noisy, const AtrousGuide& guide, const AtrousParams& p,
                      const AtrousKernels& kernels, uint64_t* taps = nullptr);

// The B3-spline tap weights h(dx)·h(dy), row-major over dy, dx ∈ [−2, 2] (exact in float).
const float* atrous_tap_weights();

}  // namespace shadowlab
