// The variance filter ("vsm": cvsm, tvsm, pvsm): moments of the stored distance, box-filtered
// (techniques/filters/moments_common/moment_filter.h), looked up bilinearly and bounded by Chebyshev's inequality with
// the variance floor and the light-bleeding reduction; Krave's max-depth test and slope moment.
#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/filters/moments_common/chebyshev.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace vsm_filter {
namespace {

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      [] { MapKey b = map_blur_key(); b.tune = "3|5"; return b; }(),
      {.name = "min_variance", .type = KeyType::Number, .def = 1e-6, .lo = 0.0, .hi = 1e6,
       .help = "variance floor, m² (1e-6: 1 mm standard deviation)",
       .store = [](MapParams& p, const KeyValue& v) { p.vsm.min_variance = v.number; }},
      {.name = "bleed", .type = KeyType::Number, .def = 0.0, .lo = 0.0, .hi = 0.99,
       .help = "light-bleeding reduction: p -> linstep(bleed, 1, p)",
       .store = [](MapParams& p, const KeyValue& v) { p.vsm.bleed = v.number; }},
      {.name = "maxdepth_eps", .type = KeyType::Number, .def = 0.0, .lo = 0.0, .hi = 1e3,
       .help = "(Krave) > 0 stores the footprint's max depth; a receiver deeper than max + eps "
               "(m) is fully shadowed",
       .store = [](MapParams& p, const KeyValue& v) { p.vsm.maxdepth_eps = v.number; }},
      {.name = "slope_moment", .type = KeyType::Flag, .def = 0,
       .help = "(Krave) M2 = d² + ¼((∂d/∂x)² + (∂d/∂y)²) per texel",
       .store = [](MapParams& p, const KeyValue& v) { p.vsm.slope_moment = v.number != 0.0; }},
      {.name = "fp32", .type = KeyType::Flag, .def = 0,
       .help = "moments (d, d²) filtered in float, the naive form kept to measure its "
               "cancellation; 0: filtered in double, stored as (mean, variance)",
       .store = [](MapParams& p, const KeyValue& v) { p.vsm.fp32 = v.number != 0.0; }},
  };
  return k;
}

// The two moments of a texel are stored interleaved in map.a (texel i's at a[2i], a[2i + 1]):
// mean and variance, or m1 and m2 in fp32 mode. A bilinear lookup's row of taps is then one
// 16-byte load and one cache line, where two planes took two of each (docs/performance_history.md).
void filter(const MapParams& p, LightMap& map) {
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    const float* d = map.dist.distance[f].data();
    if (p.vsm.fp32) {
      // A measurement mode (the naive storage): filtered as two planes, then interleaved.
      std::vector<float> m1, m2;
      filter_moments_fp32(d, face.width, face.height, p.blur, p.vsm.slope_moment, m1, m2);
      map.a[f].resize(2 * m1.size());
      for (size_t i = 0; i < m1.size(); ++i) {
        map.a[f][2 * i] = m1[i];
        map.a[f][2 * i + 1] = m2[i];
      }
    } else {
      filter_moments_double_interleaved(d, face.width, face.height, p.blur, p.vsm.slope_moment,
                                        map.a[f], face_tiles(map, f));
    }
    if (p.vsm.maxdepth_eps > 0.0)
      filter_max(d, face.width, face.height, p.blur, map.max_depth[f], map.scratch);
  }
}

// The double filter goes by tiles; the fp32 measurement mode and the max filter read whole faces.
bool by_tiles(const MapParams& p) { return !p.vsm.fp32 && !(p.vsm.maxdepth_eps > 0.0); }

// Visibility from the 4 bilinear taps' values of the planes: A (mean, or m1 in fp32 mode),
// B (variance, or m2), M (max depth; read only with maxdepth_eps > 0), weights from fx, fy.
using VsmConsts = VsmLookupConsts;  // techniques/lookup/lookup_batches.h
inline float vsm_value(const VsmConsts& k, const float* A, const float* B, const float* M, float fx,
                       float fy, float depth) {
  double w[4];
  bilinear_weights(fx, fy, w);
  const double t = double(depth);
  if (k.maxdepth) {
    const double m = std::max(std::max(M[0], M[1]), std::max(M[2], M[3]));
    if (t > m + k.eps) return 0.0f;
  }
  if (k.fp32) {
    // The naive form in float: var = E[d²] − E[d]².
    float m1 = 0.0f, m2 = 0.0f;
    for (int i = 0; i < 4; ++i) {
      m1 += float(w[i]) * A[i];
      m2 += float(w[i]) * B[i];
    }
    return chebyshev(t, m1, double(m2 - m1 * m1), k.min_var, k.bleed);
  }
  // Centred: the mixture of the four texels' (mean, variance), with no cancellation.
  double mean, var;
  mixture_moments(w, A, B, mean, var);
  return chebyshev(t, mean, var, k.min_var, k.bleed);
}

// 8 lanes at once: the interleaved moments' bilinear taps loaded by the AVX2 kernel (and the
// max-depth plane's when maxdepth_eps > 0), then vsm_value's arithmetic in AVX2 double (fp32
// mode: vsm_value lane by lane).
struct VsmBatch {
  static constexpr bool kEnabled = true;
  VsmConsts k;
  Bilinear8x2Fn bilinear8x2;
  Bilinear8Fn bilinear8;
  VsmBatchFn vsm_batch;  // the lookup batch table's
  PlaneGather moments, max_depth;
  Prefetch8Fn prefetch8;
  void prefetch(const MapLookupConsts& c, const Receivers8& r) const {
    if (prefetch8) prefetch8(c, r, moments, 2);
  }
  void operator()(const MapLookupConsts& c, const Receivers8& r, size_t, float* out) const {
    alignas(32) float v[3][4][8], fx[8], fy[8];
    bilinear8x2(c, r, moments, v, fx, fy);
    if (k.maxdepth)
      bilinear8(c, r, &max_depth, 1, v + 2, fx, fy);
    else
      std::fill(&v[2][0][0], &v[2][0][0] + 32, 0.0f);  // no max-depth plane: unread
    if (!k.fp32) {
      vsm_batch(k, v, fx, fy, r.depth, r.active, out);
      return;
    }
    for (int lane = 0; lane < 8; ++lane) {
      if (!r.active[lane]) continue;
      float A[4], B[4], M[4];
      for (int t = 0; t < 4; ++t) {
        A[t] = v[0][t][lane];
        B[t] = v[1][t][lane];
        M[t] = v[2][t][lane];
      }
      out[lane] = vsm_value(k, A, B, M, fx[lane], fy[lane], r.depth[lane]);
    }
  }
};

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double inv_far = 1.0 / double(scene.light.far);
  const VsmKeys& v = p.vsm;
  const VsmConsts k{v.min_variance * inv_far * inv_far, v.maxdepth_eps * inv_far, v.bleed,
                    v.maxdepth_eps > 0.0, v.fp32};
  auto visibility = [&](const Receiver& r) {
    const size_t fi = size_t(r.face);
    const LightFace& f = L.faces[fi];
    const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
    size_t idx[4];
    bilinear_indices(bl, f.width, idx);
    float A[4], B[4], M[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 4; ++i) {
      A[i] = map.a[fi][2 * idx[i]];
      B[i] = map.a[fi][2 * idx[i] + 1];
      if (k.maxdepth) M[i] = map.max_depth[fi][idx[i]];
    }
    return vsm_value(k, A, B, M, bl.fx, bl.fy, r.depth);
  };
  const LookupKernels& kernels = lookup_kernels(process_isa());
  VsmBatch batch{k, kernels.bilinear8_interleaved2, kernels.bilinear8,
                 lookup_batch_kernels(process_isa()).vsm_batch, plane_gather(map.a),
                 plane_gather(map.max_depth), kernels.prefetch8};
  const bool gathers = batch.bilinear8x2 && batch.bilinear8 && batch.vsm_batch &&
                       batch.moments.ok && (!k.maxdepth || batch.max_depth.ok);
  if (gathers)
    lookup_pixels(scene, g, p, map, mask, texels, visibility, batch);
  else
    lookup_pixels(scene, g, p, map, mask, texels, visibility);
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
uint64_t stored_planes(const MapParams& p) { return 2 + (p.vsm.maxdepth_eps > 0.0 ? 1 : 0); }
uint64_t tap_bytes(const MapParams& p) { return 4 * stored_planes(p); }

}  // namespace
}  // namespace vsm_filter

const MapFilterOps kVarianceMap = {
    "vsm", "variance shadow map", MapFilter::Variance,
    vsm_filter::keys, vsm_filter::filter, vsm_filter::lookup,
    vsm_filter::taps_per_lookup, vsm_filter::tap_bytes, vsm_filter::stored_planes,
    vsm_filter::by_tiles, false};

}  // namespace shadowlab
