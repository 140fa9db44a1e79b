// The exponential variance filter ("evsm": cevsm, tevsm, pevsm; Lauritzen & McCool 2008): the
// normalised distance d is warped to d' = 2d − 1 in [−1, 1], then to v₊ = e^(c₊·d') and, with
// moments=4, to v₋ = −e^(−c₋·d'); each warp's moments are box-filtered like VSM's
// (techniques/filters/moments_common/moment_filter.h: double, stored as mean and variance) and bounded by Chebyshev's
// inequality at the receiver's warped depth; EVSM4 takes the smaller of the two bounds. Both
// warps increase with d, so "the receiver lies beyond the occluders" keeps its sense. The
// exponential warp shrinks the overlap that makes VSM leak light (docs/design.md §6, EVSM).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "core/exp_log.h"
#include "techniques/filters/moments_common/chebyshev.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace evsm_filter {
namespace {

// The largest exponent whose square e^(2c) is still finite in float: ln(FLT_MAX)/2.
constexpr double kMaxExponent = 44.36;

// An exponent in (kMaxExponent, parse_hi] is read, then refused with the reason.
void check_exponent(const KeyCheck& c, const char* key, double value) {
  if (value > kMaxExponent)
    throw InputError(c.flag, fmt::format("{}: '{}' = {:g} overflows the stored moments: e^(2c) "
                                         "exceeds float's range above c = {:g}",
                                         c.name, key, value, kMaxExponent));
}

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      map_blur_key(),
      {.name = "moments", .type = KeyType::Choice, .def_word = "2", .choices = "2|4",
       .help = "2: the positive warp e^(c_pos·d'); 4: also the negative warp −e^(−c_neg·d')",
       .tune = "2|4",
       .store = [](MapParams& p, const KeyValue& v) { p.evsm.moments = std::stoi(v.word); }},
      {.name = "c_pos", .type = KeyType::Number, .def = 40.0, .lo = 0.01, .hi = kMaxExponent,
       .parse_hi = 1e4, .help = "positive exponent (40: the fp32 default of the literature)",
       .store = [](MapParams& p, const KeyValue& v) { p.evsm.c_pos = v.number; },
       .check = [](const KeyCheck& c, MapParams& p) { check_exponent(c, "c_pos", p.evsm.c_pos); }},
      {.name = "c_neg", .type = KeyType::Number, .def = 5.0, .lo = 0.01, .hi = kMaxExponent,
       .parse_hi = 1e4, .help = "negative exponent",
       .store = [](MapParams& p, const KeyValue& v) { p.evsm.c_neg = v.number; },
       .check = [](const KeyCheck& c, MapParams& p) { check_exponent(c, "c_neg", p.evsm.c_neg); }},
      {.name = "min_variance", .type = KeyType::Number, .def = 1e-6, .lo = 0.0, .hi = 1e6,
       .help = "variance floor of the distance, m², carried into each warp by its slope at the "
               "receiver",
       .store = [](MapParams& p, const KeyValue& v) { p.evsm.min_variance = v.number; }},
      {.name = "bleed", .type = KeyType::Number, .def = 0.0, .lo = 0.0, .hi = 0.99,
       .help = "light-bleeding reduction, as for vsm",
       .store = [](MapParams& p, const KeyValue& v) { p.evsm.bleed = v.number; }},
  };
  return k;
}

// A texel's moments are stored interleaved in map.a, as VSM's and MSM's (variance_map.cpp): the
// positive warp's mean and variance, then (4 moments) the negative warp's, texel i's at
// a[S·i + 0..S−1] with S = 2 or 4; one load per tap row fetches them all.
int evsm_stride(const MapParams& p) { return p.evsm.moments == 4 ? 4 : 2; }

void filter(const MapParams& p, LightMap& map) {
  const int s = evsm_stride(p);
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    const float* d = map.dist.distance[f].data();
    filter_warped_moments_interleaved(d, face.width, face.height, p.blur, p.evsm.c_pos, 1.0, s,
                                      0, map.a[f], face_tiles(map, f));
    if (s == 4)
      filter_warped_moments_interleaved(d, face.width, face.height, p.blur, p.evsm.c_neg, -1.0,
                                        4, 2, map.a[f], face_tiles(map, f));
  }
}

using EvsmConsts = EvsmLookupConsts;  // techniques/lookup/lookup_batches.h

// One warp's bound at normalised receiver depth t: the mixture of the 4 taps' moments (A mean,
// B variance), the floor carried into the warp by its slope dv/dt = 2c·e^(±c·t') at the
// receiver (first-order propagation of a distance variance), then Chebyshev.
float warp_bound(const EvsmConsts& k, const double w[4], const float* A, const float* B, double t,
                 double c, double sign) {
  const double e = exp_d(sign * c * (2.0 * t - 1.0));
  const double slope = 2.0 * c * e;
  double mean, var;
  mixture_moments(w, A, B, mean, var);
  return chebyshev(sign * e, mean, var, k.min_var * slope * slope, k.bleed);
}

// Visibility from the 4 bilinear taps of the planes (P: positive mean, variance; N: negative).
float evsm_value(const EvsmConsts& k, const float* PA, const float* PB, const float* NA,
                 const float* NB, float fx, float fy, float depth) {
  double w[4];
  bilinear_weights(fx, fy, w);
  const double t = double(depth);
  const float pos = warp_bound(k, w, PA, PB, t, k.c_pos, 1.0);
  if (!k.four) return pos;
  return std::min(pos, warp_bound(k, w, NA, NB, t, k.c_neg, -1.0));
}

// 8 lanes at once: each warp's interleaved bilinear taps loaded by the AVX2 kernel, then
// evsm_value's arithmetic in AVX2 double (the lookup batch table's evsm_batch). Used only where
// the AVX2 kernels exist (the scalar tables' bilinear8_interleaved2 and evsm_batch are null, and
// the scalar loop runs evsm_value).
struct EvsmBatch {
  static constexpr bool kEnabled = true;
  EvsmConsts k;
  Bilinear8x2Fn taps;  // the 2- or 4-value kernel
  EvsmBatchFn evsm_batch;
  PlaneGather moments;  // a
  Prefetch8Fn prefetch8;
  void prefetch(const MapLookupConsts& c, const Receivers8& r) const {
    if (prefetch8) prefetch8(c, r, moments, k.four ? 4 : 2);
  }
  void operator()(const MapLookupConsts& c, const Receivers8& r, size_t, float* out) const {
    alignas(32) float v[4][4][8], fx[8], fy[8];
    taps(c, r, moments, v, fx, fy);
    evsm_batch(k, v, fx, fy, r.depth, out);
  }
};

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double inv_far = 1.0 / double(scene.light.far);
  const EvsmKeys& e = p.evsm;
  const EvsmConsts k{e.c_pos, e.c_neg, e.min_variance * inv_far * inv_far, e.bleed,
                     e.moments == 4};
  const int s = evsm_stride(p);
  auto visibility = [&](const Receiver& r) {
    const size_t fi = size_t(r.face);
    const LightFace& f = L.faces[fi];
    const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
    size_t idx[4];
    bilinear_indices(bl, f.width, idx);
    float P[4][4] = {};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < s; ++j) P[j][i] = map.a[fi][size_t(s) * idx[i] + size_t(j)];
    }
    return evsm_value(k, P[0], P[1], P[2], P[3], bl.fx, bl.fy, r.depth);
  };
  const LookupKernels& kernels = lookup_kernels(process_isa());
  EvsmBatch batch{k, k.four ? kernels.bilinear8_interleaved4 : kernels.bilinear8_interleaved2,
                  lookup_batch_kernels(process_isa()).evsm_batch, plane_gather(map.a),
                  kernels.prefetch8};
  const bool gathers = batch.taps != nullptr && batch.evsm_batch != nullptr && batch.moments.ok;
  if (gathers)
    lookup_pixels(scene, g, p, map, mask, texels, visibility, batch);
  else
    lookup_pixels(scene, g, p, map, mask, texels, visibility);
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
uint64_t stored_planes(const MapParams& p) { return p.evsm.moments == 4 ? 4 : 2; }
uint64_t tap_bytes(const MapParams& p) { return 4 * stored_planes(p); }

}  // namespace
}  // namespace evsm_filter

const MapFilterOps kExponentialVarianceMap = {
    "evsm", "exponential variance shadow map", MapFilter::ExponentialVariance,
    evsm_filter::keys, evsm_filter::filter, evsm_filter::lookup,
    evsm_filter::taps_per_lookup, evsm_filter::tap_bytes, evsm_filter::stored_planes,
    map_filter_always_by_tiles, false};

}  // namespace shadowlab
