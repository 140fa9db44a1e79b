#pragma once
// Filters that turn a face's normalised radial distances (techniques/pipeline/face_render.h) into the
// filtered maps of the variance and exponential shadow maps. All are box filters of odd width k
// over a w × h image (separable, but VSM's and EVSM's at k = 3: one 9-tap window per texel),
// clamp-to-edge at the borders (the faces' guard bands keep
// looked-up texels away from them). Empty texels (+inf, nothing seen) count as distance 1,
// the light's range. Each output texel depends only on its inputs and a fixed order of
// additions, so results are identical for any thread count.
#include <vector>

namespace shadowlab {

struct FaceTiles;  // techniques/pipeline/texel_tiles.h

// Working storage of the max filter, kept by the caller across calls so that repeated builds
// reuse their memory (fresh pages cost ~20 µs each on the VMs we measure on). The moment and
// ESM filters need none: they work per chunk of rows in small buffers of their own.
struct FilterScratch {
  std::vector<float> tmp_f;
};

// VSM moments filtered in double and stored centred: mean = E[d] and variance = E[d²] − E[d]²,
// each rounded to float once at the end. Storing the variance itself keeps its relative
// precision: the fp32 difference of second moments near d = 1 loses everything below ~1.2e-7.
// k = 3 without the slope term (the default blur) takes each texel's 9-tap window in float
// centred on its own distance instead (techniques/filters/moments_common/centred_window3.h: cheaper, and within
// 1.7e-5 of the variance and one ulp of the mean plus 26·2^-24 of the window's σ).
// slope_term adds ¼((∂d/∂x)² + (∂d/∂y)²) per texel to E[d²] (Krave), with each derivative the
// smaller-magnitude one-sided difference (so a silhouette's jump does not count).
void filter_moments_double(const float* dist, int w, int h, int k, bool slope_term,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles = nullptr);
// filter_moments_double's values in one interleaved plane: texel i's mean at mean_variance[2i],
// its variance at [2i + 1] (the VSM lookup's storage: one load fetches both of a tap's values,
// and a bilinear footprint row touches one cache line instead of two).
void filter_moments_double_interleaved(const float* dist, int w, int h, int k, bool slope_term,
                                       std::vector<float>& mean_variance,
                                       const FaceTiles* tiles = nullptr);
// The functions below but the fp32 and max filters take `tiles` (nullptr: every texel): with
// it they write only the texels of the needed tiles (techniques/pipeline/texel_tiles.h), each with the
// bits the whole image's filter gives it (the same inputs through the same additions: a tile's
// windows read its neighbours' unfiltered distances, clamped at the image's edges only), and
// leave the other texels as they were.
// The naive form, kept to measure it: (d, d²) summed and stored in float.
void filter_moments_fp32(const float* dist, int w, int h, int k, bool slope_term,
                         std::vector<float>& m1, std::vector<float>& m2);
// Maximum of d over the k × k footprint (Krave's max-depth test).
void filter_max(const float* dist, int w, int h, int k, std::vector<float>& out,
                FilterScratch& scratch);
// ESM occluder term in log space: out = log( box_k( exp(c·d) ) ), i.e. c × the filtered
// occluder depth, for any c in (0, 700]. Computed as c·d_min + log(box_k(exp(c·(d − d_min))))
// with d_min the image's smallest distance, so every exponential lies in [1, e^c] (finite in
// double for c <= 709), summed in double so that no sum cancels; the naive fp32 exp(c·d)
// overflows once c·d > 88.7. The exponent c·(d − d_min) is rounded once to float and exp and ln
// are core/exp_log.h's exp_wide and log_wide (float precision, double range, vectorized, the
// same bits on any x86-64): the stored value is a float, and the error they add, at most
// c·2^-24 + 5e-7, is about what the float's own rounding and the lookup's float exponent add
// (docs/techniques/esm.md). For k <= 9, every tile of 32 × 32 texels whose windows' range
// allows it (c·(hi − lo)/2 <= ~80) is instead filtered in float around its own middle
// distance (techniques/filters/esm/esm_float_tiles.h: twice the lanes per instruction, within
// (X + 2k + 4)·2^-24 + 2.3e-7 + half an ulp, X <= 80 the tile's largest exponent); the rest as
// above. Each texel's value depends on its tile's inputs only, so tiles change no bits.
// face_min: the smallest of the w × h distances (FaceDistances::min_distance), which saves the
// filter a pass over the whole image; nullptr: the filter finds it (the oracle always does).
void filter_esm_log(const float* dist, int w, int h, int k, double c, std::vector<float>& out,
                    const FaceTiles* tiles = nullptr, const float* face_min = nullptr);

// EVSM's warped moments (Lauritzen & McCool 2008): v = sign·e^(sign·c·(2d − 1)) per texel
// (d = the distance with "nothing seen" as 1, warped to [−1, 1]; sign +1 the positive warp,
// −1 the negative one), box-filtered in double and stored as mean and variance floats like
// filter_moments_double (k = 3: its centred float window of v). |v| <= e^c and v² <= e^(2c):
// finite in float for c <= 44.36. The warp
// itself is made in float (exp_f of float(sign·c)·((d + d) − 1)): its rounding, ~4e-6 of v at
// c = 44, is what a change of d by 1–2 of its own float ulps does, and v and v² are then
// summed in double, where the variance's cancellation needs it (docs/techniques/evsm.md).
void filter_warped_moments(const float* dist, int w, int h, int k, double c, double sign,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles = nullptr);
// filter_warped_moments' values in an interleaved plane of `stride` floats per texel (texel i's
// mean at out[stride·i + first], variance at + 1; stride 2 with first 0, or stride 4 with first 0
// or 2, so EVSM4 keeps both warps' pairs of a texel in 16 bytes), the EVSM lookup's storage.
// out is resized to stride·w·h floats when its size differs (the other slots are kept).
void filter_warped_moments_interleaved(const float* dist, int w, int h, int k, double c,
                                       double sign, int stride, int first, std::vector<float>& out,
                                       const FaceTiles* tiles = nullptr);

// MSM's power moments (Peters & Klein 2015): d, d², d³, d⁴ per texel (d = the distance with
// "nothing seen" as 1), box-filtered in float and stored as floats in out[0..3]. Why float is exact
// enough here (float where the evidence shows it is; docs/techniques/msm.md): the moments of d ∈
// [0, 1] are positive, so their sums have no cancellation (relative error below (2k + 2)·2^-24,
// measured ~1e-7 at k = 3); the masks move by about twice what a random change of every distance by
// one float ulp moves them, the stability rows at α ≥ 3e-6 not at all, and the scores of Table I by
// at most one unit of their last digit.
void filter_power_moments(const float* dist, int w, int h, int k, std::vector<float>* out,
                          const FaceTiles* tiles = nullptr);
// filter_power_moments' values in one interleaved plane: texel i's E[d^(c+1)] at moments[4i + c]
// (the MSM lookup's storage: one 32-byte load per tap row fetches both taps' four moments).
void filter_power_moments_interleaved(const float* dist, int w, int h, int k,
                                      std::vector<float>& moments,
                                      const FaceTiles* tiles = nullptr);

// The filters above run kernels with the box width k a compile-time constant for k = 1, 3,
// 5, 7, 9 (sums kept in registers; AVX-512, AVX2 or baseline picked at load time) and
// runtime-k row loops otherwise. These run the runtime-k loops for every k (VSM's and EVSM's
// k = 3 window its scalar loop): the oracle the fixed-width kernels must equal bit for bit
// (tests/techniques/moment_filter_test.cpp).
void filter_moments_double_oracle(const float* dist, int w, int h, int k, bool slope_term,
                                  std::vector<float>& mean, std::vector<float>& variance,
                                  const FaceTiles* tiles = nullptr);
void filter_esm_log_oracle(const float* dist, int w, int h, int k, double c,
                           std::vector<float>& out, const FaceTiles* tiles = nullptr);
void filter_warped_moments_oracle(const float* dist, int w, int h, int k, double c, double sign,
                                  std::vector<float>& mean, std::vector<float>& variance,
                                  const FaceTiles* tiles = nullptr);

void filter_power_moments_oracle(const float* dist, int w, int h, int k, std::vector<float>* out,
                                 const FaceTiles* tiles = nullptr);

}  // namespace shadowlab
