#pragma once
// The filters' lookup arithmetic for 8 pixels at once, as a kernel family (docs/simd.md): what
// each filter computes from a batch's taps (techniques/lookup/map_lookup_simd.h loads them) in vector
// lanes, each kernel performing its filter's scalar operations in their order, so that every
// lane gets the scalar lookup's bits: ESM's combine (exponential_map.cpp), VSM's and EVSM's
// Chebyshev bounds (variance_map.cpp, exponential_variance_map.cpp), MSM's reconstruction
// (moment_shadow_map.cpp, techniques/filters/msm/moment_bound.h), rotated Poisson PCF (depth_compare.cpp)
// and PCSS's blocker search and PCF stage (pcss.cpp).
//
// The scalar table has no kernels (nullptr): its callers run their scalar lookup per pixel,
// the oracle. The AVX-512 table is the AVX2 one except for MSM's reconstruction in 8 lanes (the
// others are bound by their gathers). Tests, for every table the CPU has:
// LookupSimd.FilterBatchesMatchTheScalarOracle (tests/techniques/lookup_simd_test.cpp: whole
// lookups against the scalar loops) and MomentBound.EveryTablesLanesGiveTheScalarBits.
#include <cstdint>

#include "core/isa.h"
#include "core/math.h"

namespace shadowlab {

struct MapLookupConsts;  // techniques/lookup/map_lookup_simd.h
struct Receivers8;

// VSM's lookup constants: variance floor, max-depth epsilon (normalised), light-bleeding
// reduction, whether the max-depth plane is read, whether the moments are fp32 (then the lookup
// runs vsm_value per lane).
struct VsmLookupConsts {
  double min_var, eps, bleed;
  bool maxdepth, fp32;
};
// EVSM's: the two warps' exponents, the variance floor of the normalised distance, the bleed
// reduction, whether the negative warp is stored (4 moments).
struct EvsmLookupConsts {
  double c_pos, c_neg;
  double min_var;
  double bleed;
  bool four;
};
// MSM's: the moment bias α, the Hausdorff variant, the 16-bit store.
struct MsmLookupConsts {
  double alpha;
  bool hausdorff, quantize16;
};

// ESM: out = min(Σ bilinear w · exp_f(clamp(z − ct, −87, 80)), 1) of the four taps z[0..3].
using EsmCombine8Fn = void (*)(const float (*z)[8], const float* fx, const float* fy,
                               const float* ct, float* out);
// VSM (not fp32): vsm_value of each lane from the taps v[0] (means), v[1] (variances), v[2]
// (max depths, when k.maxdepth).
using VsmBatchFn = void (*)(const VsmLookupConsts& k, const float (*v)[4][8], const float* fx,
                            const float* fy, const float* depth, const int32_t* active,
                            float* out);
// EVSM: evsm_value of each lane from the taps v[0], v[1] (the positive warp's mean, variance)
// and v[2], v[3] (the negative warp's, when k.four).
using EvsmBatchFn = void (*)(const EvsmLookupConsts& k, const float (*v)[4][8], const float* fx,
                             const float* fy, const float* depth, float* out);
// MSM from each of N batches' bilinearly mixed moments (AVX2, in halves of 4 lanes: N = 1 or 2).
using MsmMixedFn = void (*)(const MsmLookupConsts& k, const double (*const* mixed)[8],
                            const float* const* depth, float* const* out);
// MSM from each of N batches' taps (AVX-512, in 8 lanes: N = 1 or 4).
using MsmTapsFn = void (*)(const MsmLookupConsts& k, const float (*const* v)[4][8],
                           const float* const* fx, const float* const* fy,
                           const float* const* depth, float* const* out);
// msm_intensity on lanes m[i][lane] (moment i + 1), z[lane]: the table's reconstruction alone,
// for its tests.
using MsmIntensityFn = void (*)(const double (*m)[32], const double* z, double alpha,
                                bool hausdorff, double* out);
// Rotated Poisson PCF (no plane gradient) of the 8 receivers: each lane's rotation (cosv, sinv),
// the disk's n points, its radius in texels.
using PoissonBatchFn = void (*)(const MapLookupConsts& c, const Receivers8& r, const float* cosv,
                                const float* sinv, const vec2* points, int n, float radius,
                                float* out);
// PCSS's blocker search over the disk's n points (each lane's search radius rs and rotation
// (cs, sn), plane gradient (gx, gy)): per lane the sum of the blockers' distances, their count,
// and whether a tap left the face's image [1, w − 1] × [1, h − 1] (outside: all ones).
using PcssSearchFn = void (*)(const MapLookupConsts& c, const Receivers8& r, const float* rs,
                              const float* cs, const float* sn, const float* gx,
                              const float* gy, const int32_t* active, const vec2* points, int n,
                              double* sums, int32_t* counts, float* outside);
// PCSS's rotated Poisson PCF over each lane's radius for the lanes in `live` (all ones): the
// visibility, and whether a tap left the image.
using PcssPcfFn = void (*)(const MapLookupConsts& c, const Receivers8& r, const float* radius,
                           const float* cs, const float* sn, const float* gx, const float* gy,
                           const int32_t* active, const int32_t* live, const vec2* points,
                           int n, float* vis, float* outside);

struct LookupBatchKernels {
  Isa isa;  // the instruction set of the widest kernel in the table
  EsmCombine8Fn esm_combine8;
  VsmBatchFn vsm_batch;
  EvsmBatchFn evsm_batch;
  MsmMixedFn msm_mixed1, msm_mixed2;  // AVX2's
  MsmTapsFn msm_taps1, msm_taps4;     // AVX-512's (nullptr in the AVX2 table)
  MsmIntensityFn msm_intensity, msm_intensity_groups;
  int msm_lanes, msm_lanes_groups;  // the lanes they take: 4 and 2 × 4, or 8 and 4 × 8
  PoissonBatchFn poisson_batch;
  PcssSearchFn pcss_search;
  PcssPcfFn pcss_pcf;
};
const LookupBatchKernels& lookup_batch_kernels(Isa isa);

}  // namespace shadowlab
