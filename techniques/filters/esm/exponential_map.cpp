// The exponential filter ("esm": cesm, tesm, pesm): the occluder term exp(c·z) box-filtered in
// log space (techniques/filters/moments_common/moment_filter.h), looked up bilinearly as Σ w·exp(c·z_occ − c·t).
#include <algorithm>

#include <fmt/format.h>
#include <cmath>
#include <cstdio>

#include "core/isa.h"
#include "core/error.h"
#include "core/exp_log.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace esm_filter {
namespace {

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      [] { MapKey b = map_blur_key(); b.tune = "3|5"; return b; }(),
      // exp(c·Δ) with Δ <= 1 must stay below DBL_MAX (ln ≈ 709.8) in the filter; see moment_filter.h.
      {.name = "c", .type = KeyType::Number, .def = 200.0, .lo = 0.01, .hi = 700.0,
       .help = "exponent on the normalised distance (|p - L| / far); the log-space filter "
               "allows any c <= 700",
       .store = [](MapParams& p, const KeyValue& v) { p.esm.c = v.number; }},
  };
  return k;
}

void filter(const MapParams& p, LightMap& map) {
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    filter_esm_log(map.dist.distance[f].data(), face.width, face.height, p.blur, p.esm.c, map.a[f],
                   face_tiles(map, f),
                   f < map.dist.min_distance.size() ? &map.dist.min_distance[f] : nullptr);
  }
}

// One occluder term, e^(z − c·t) in float (core/exp_log.h's exp_f, whose steps the AVX2 batch
// repeats, so both give the same bits: techniques/lookup/lookup_batches.h). The exponent is clamped to [-87, 80]: e^80 ≈ 5.5e34
// keeps four terms finite in float (any such tap already makes the sum >= 1 unless its weight
// is below e^-80, and the result is clamped to 1); below -87 a term counts as e^-87 ≈ 1.6e-38
// instead of less, a difference far below float's resolution of any sum it enters.
inline float occluder_term(float z, float ct) {
  return exp_f(std::max(std::min(z - ct, 80.0f), -87.0f));
}

// Σ w·exp(c·z_occ − c·t): the bilinear filter of exp(c·z) times exp(−c·t), clamped to 1.
inline float esm_combine(float z00, float z10, float z01, float z11, float fx, float fy, float ct) {
  const float v = (1.0f - fy) * ((1.0f - fx) * occluder_term(z00, ct) + fx * occluder_term(z10, ct)) +
                  fy * ((1.0f - fx) * occluder_term(z01, ct) + fx * occluder_term(z11, ct));
  return std::min(v, 1.0f);
}

// esm_combine for 8 lanes: the table's kernel (techniques/lookup/lookup_batches.h: the same operations
// in the same order), or lane by lane where it has none.
void esm_combine8(EsmCombine8Fn kernel, const float (*z)[8], const float* fx, const float* fy,
                  const float* ct, float* out) {
  if (kernel) {
    kernel(z, fx, fy, ct, out);
    return;
  }
  for (int k = 0; k < 8; ++k)
    out[k] = esm_combine(z[0][k], z[1][k], z[2][k], z[3][k], fx[k], fy[k], ct[k]);
}

// 8 lanes at once: the bilinear taps of plane a gathered by the AVX2 kernel (or read lane by
// lane where it cannot run), then esm_combine8.
template <class Taps>
struct EsmBatch {
  static constexpr bool kEnabled = true;
  const Taps& taps_of;
  float cf;
  EsmCombine8Fn combine8;  // the lookup batch table's, nullptr in the scalar one
  Bilinear8Fn bilinear8;
  PlaneGather a;
  Prefetch8Fn prefetch8;
  void prefetch(const MapLookupConsts& c, const Receivers8& r) const {
    if (prefetch8 && a.ok) prefetch8(c, r, a, 1);
  }
  void operator()(const MapLookupConsts& c, const Receivers8& r, size_t, float* out) const {
    alignas(32) float z[1][4][8], fx[8], fy[8], ct[8];
    if (bilinear8 && a.ok) {
      bilinear8(c, r, &a, 1, z, fx, fy);
    } else {
      for (int k = 0; k < 8; ++k) {
        float z4[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        fx[k] = fy[k] = 0.0f;
        // Inactive lanes read nothing (their face may not be rendered); their result is unused.
        if (r.active[k]) taps_of(r.face[k], vec2(r.sx[k], r.sy[k]), z4, fx[k], fy[k]);
        for (int i = 0; i < 4; ++i) z[0][i][k] = z4[i];
      }
    }
    for (int k = 0; k < 8; ++k) ct[k] = cf * r.depth[k];
    esm_combine8(combine8, z[0], fx, fy, ct, out);
  }
};

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const float cf = float(p.esm.c);
  auto taps = [&](int face, vec2 st, float* z4, float& fx, float& fy) {
    const LightFace& f = L.faces[size_t(face)];
    const float* z = map.a[size_t(face)].data();
    const Bilinear bl = bilinear_taps(st, f.width, f.height);
    size_t idx[4];
    bilinear_indices(bl, f.width, idx);
    for (int i = 0; i < 4; ++i) z4[i] = z[idx[i]];
    fx = bl.fx;
    fy = bl.fy;
  };
  auto visibility = [&](const Receiver& r) {
    float z4[4], fx, fy;
    taps(r.face, r.st, z4, fx, fy);
    return esm_combine(z4[0], z4[1], z4[2], z4[3], fx, fy, cf * r.depth);
  };
  const LookupKernels& kernels = lookup_kernels(process_isa());
  lookup_pixels(scene, g, p, map, mask, texels, visibility,
                EsmBatch<decltype(taps)>{taps, cf,
                                         lookup_batch_kernels(process_isa()).esm_combine8,
                                         kernels.bilinear8, plane_gather(map.a),
                                         kernels.prefetch8});
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 1; }

}  // namespace
}  // namespace esm_filter

const MapFilterOps kExponentialMap = {
    "esm", "exponential shadow map", MapFilter::Exponential,
    esm_filter::keys, esm_filter::filter, esm_filter::lookup,
    esm_filter::taps_per_lookup, esm_filter::tap_bytes, esm_filter::stored_planes,
    map_filter_always_by_tiles, true};

}  // namespace shadowlab
