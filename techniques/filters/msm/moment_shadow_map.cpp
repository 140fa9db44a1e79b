// The moment filter ("msm": cmsm, tmsm, pmsm; Peters & Klein 2015): the power moments d, d²,
// d³, d⁴ of the stored normalised distance, box-filtered in float (techniques/filters/moments_common/moment_filter.h)
// and stored as 4 floats per texel, or through the optimized 16-bit quantization; looked up
// bilinearly (the moments mix linearly, so the 4 taps' weighted sum is the footprint's
// moments) and turned into the sharpest lower bound on the occluded fraction
// (techniques/filters/msm/moment_bound.h: Hamburger or Hausdorff). docs/design.md §6, MSM.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/isa.h"
#include "core/parallel.h"
#include "techniques/filters/moments_common/chebyshev.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"
#include "techniques/filters/msm/moment_bound.h"
#include "techniques/filters/moments_common/moment_rows.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace msm_filter {
namespace {

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      map_blur_key(),
      {.name = "variant", .type = KeyType::Choice, .def_word = "hamburger",
       .choices = "hamburger|hausdorff",
       .help = "the moment problem's support: hamburger (ℝ) or hausdorff ([0, 1])",
       .store = [](MapParams& p, const KeyValue& v) { p.msm.hausdorff = v.word == "hausdorff"; }},
      {.name = "quantize16", .type = KeyType::Flag, .def = 0,
       .help = "store 4 × 16 bits (the optimized quantization) instead of 4 × fp32",
       .store = [](MapParams& p, const KeyValue& v) { p.msm.quantize16 = v.number != 0.0; }},
      {.name = "alpha", .type = KeyType::Number, .def = 3e-6, .lo = 0.0, .hi = 0.5,
       .help = "moment bias toward (½, ½, ½, ½); 3e-5 by default with quantize16, whose coarser "
               "rounding needs it",
       .store = [](MapParams& p, const KeyValue& v) { p.msm.alpha = v.number; },
       .check = [](const KeyCheck& c, MapParams& p) {
         if (!c.value.given && p.msm.quantize16) p.msm.alpha = 3e-5;
       }},
  };
  return k;
}

// The four moments of a texel are stored interleaved in map.a (texel i's at a[4i + 0..3]): a
// bilinear lookup's row of taps is one 32-byte load and one cache line, where four planes took
// four of each (docs/performance_history.md).
void filter(const MapParams& p, LightMap& map) {
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    const FaceTiles* tiles = face_tiles(map, f);
    filter_power_moments_interleaved(map.dist.distance[f].data(), face.width, face.height,
                                     p.blur, map.a[f], tiles);
    if (!p.msm.quantize16) continue;
    // The filtered texels' moments through the 16-bit store (msm_encode16, clamped to [0, 1],
    // rounded to the nearest multiple of 1/65535: a UNORM16 channel), band by band.
    const Quantize16Fn quantize16 = moment_row_kernels(process_isa()).quantize16;
    float* const mv = map.a[f].data();
    const int bands = (face.height + kTexelTile - 1) / kTexelTile;
    parallel_for_chunks(size_t(bands), 1, [&](size_t b0, size_t b1) {
      std::vector<TexelSpan> spans;
      for (size_t band = b0; band < b1; ++band) {
        tile_spans(tiles, int(band), face.width, spans);
        const int y1 = std::min(face.height, int(band + 1) * kTexelTile);
        for (int y = int(band) * kTexelTile; y < y1; ++y)
          for (const TexelSpan& s : spans)
            quantize16(size_t(s.x1 - s.x0),
                       mv + 4 * (size_t(y) * size_t(face.width) + size_t(s.x0)));
      }
    });
  }
}

using MsmConsts = MsmLookupConsts;  // techniques/lookup/lookup_batches.h

// Visibility from the 4 bilinear taps of the 4 planes (P[plane][tap]).
float msm_value(const MsmConsts& k, const float (*P)[4], float fx, float fy, float depth) {
  double w[4];
  bilinear_weights(fx, fy, w);
  double m[4];
  for (int j = 0; j < 4; ++j) {
    m[j] = 0.0;
    for (int i = 0; i < 4; ++i) m[j] += w[i] * P[j][i];
  }
  if (k.quantize16) {
    const double q[4] = {m[0], m[1], m[2], m[3]};
    msm_decode16(q, m);
  }
  return float(1.0 - msm_intensity(m, double(depth), k.alpha, k.hausdorff));
}

// 8 lanes at once: msm_value's arithmetic in double. With AVX-512, the interleaved moments'
// bilinear taps loaded by the AVX2 kernel, then the mix and the reconstruction in 8 lanes;
// with AVX2, the mixed moments from bilinear8_mix4 (lane by lane, no tap transpose), then
// the reconstruction in halves of 4. Used only where the AVX2 kernels exist. The lookup
// loop hands it kGroups batches at a time (map_lookup.h): the reconstruction is a serial chain
// of divisions and a square root per batch (7 divisions then, 2 now), and with AVX-512 4
// independent chains side by side took the room100k lookup from 7.0-7.4 to 5.1-5.9 ms where 2
// took it to 5.4-6.3 and 8 gained nothing (AMD EPYC, alternating rounds of technique_bench).
// The AVX2 form takes them as pairs of batches (4 halves of 4 lanes side by side).
struct MsmBatch {
  static constexpr bool kEnabled = true;
  static constexpr int kGroups = 4;
  MsmConsts k;
  Bilinear8x2Fn bilinear8x4;  // the taps, for the AVX-512 form
  Mix8x4Fn mix4;              // the mixed moments, for the AVX2 form
  PlaneGather moments;  // a: moments 1 to 4 per texel
  Prefetch8Fn prefetch8;
  const LookupBatchKernels* batches;  // the reconstruction's kernels (techniques/lookup/lookup_batches.h)
  // The reconstruction in 8 lanes (the AVX-512 table's msm_taps) or in two halves of 4.
  bool avx512() const { return batches->msm_taps1 != nullptr; }
  static constexpr int kAvx2Groups = 2;  // batches per msm_mixed2 call in groups()
  bool grouped() const { return true; }
  void prefetch(const MapLookupConsts& c, const Receivers8& r) const {
    if (prefetch8) prefetch8(c, r, moments, 4);
  }
  void operator()(const MapLookupConsts& c, const Receivers8& r, size_t, float* out) const {
    const float* dp = r.depth;
    if (avx512()) {
      alignas(32) float v[4][4][8], fx[8], fy[8];
      bilinear8x4(c, r, moments, v, fx, fy);
      const float(*vp)[4][8] = v;
      const float *fxp = fx, *fyp = fy;
      batches->msm_taps1(k, &vp, &fxp, &fyp, &dp, &out);
    } else {
      alignas(32) double mixed[4][8];
      mix4(c, r, moments, mixed);
      const double(*mp)[8] = mixed;
      batches->msm_mixed1(k, &mp, &dp, &out);
    }
  }
  // kGroups batches at once: in 8 lanes with AVX-512, else kAvx2Groups at a time in halves of 4.
  void groups(const MapLookupConsts& c, const Receivers8* r, float (*out)[8]) const {
    constexpr int G = kGroups;
    const float* dp[G];
    float* op[G];
    for (int h = 0; h < G; ++h) {
      dp[h] = r[h].depth;
      op[h] = out[h];
    }
    if (avx512()) {
      alignas(32) float v[G][4][4][8], fx[G][8], fy[G][8];
      const float(*vp[G])[4][8];
      const float *fxp[G], *fyp[G];
      for (int h = 0; h < G; ++h) {
        bilinear8x4(c, r[h], moments, v[h], fx[h], fy[h]);
        vp[h] = v[h];
        fxp[h] = fx[h];
        fyp[h] = fy[h];
      }
      batches->msm_taps4(k, vp, fxp, fyp, dp, op);
      return;
    }
    alignas(32) double mixed[G][4][8];
    const double(*mp[G])[8];
    for (int h = 0; h < G; ++h) {
      mix4(c, r[h], moments, mixed[h]);
      mp[h] = mixed[h];
    }
    for (int h = 0; h < G; h += kAvx2Groups) {
      // A pair of batches with no active lane (uncovered or unlit pixels) needs no
      // reconstruction: the lookup loop keeps those lanes' masks (merge8).
      bool any = false;
      for (int j = h; j < h + kAvx2Groups; ++j)
        for (int lane = 0; lane < 8; ++lane) any |= r[j].active[lane] != 0;
      if (any) batches->msm_mixed2(k, mp + h, dp + h, op + h);
    }
  }
};

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const MsmConsts k{p.msm.alpha, p.msm.hausdorff, p.msm.quantize16};
  auto visibility = [&](const Receiver& r) {
    const size_t fi = size_t(r.face);
    const LightFace& f = L.faces[fi];
    const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
    size_t idx[4];
    bilinear_indices(bl, f.width, idx);
    float P[4][4];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) P[j][i] = map.a[fi][4 * idx[i] + size_t(j)];
    return msm_value(k, P, bl.fx, bl.fy, r.depth);
  };
  const LookupKernels& kernels = lookup_kernels(process_isa());
  MsmBatch batch{k, kernels.bilinear8_interleaved4, kernels.bilinear8_mix4, plane_gather(map.a),
                 kernels.prefetch8, &lookup_batch_kernels(family_isa(IsaFamily::msm_batch))};
  const bool gathers = batch.bilinear8x4 != nullptr && batch.mix4 != nullptr &&
                       batch.batches->msm_mixed1 != nullptr && batch.moments.ok;
  if (gathers)
    lookup_pixels(scene, g, p, map, mask, texels, visibility, batch);
  else
    lookup_pixels(scene, g, p, map, mask, texels, visibility);
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
// 4 fp32 moments = 4 float planes; 4 × 16 bits = the bytes of 2.
uint64_t stored_planes(const MapParams& p) { return p.msm.quantize16 ? 2 : 4; }
uint64_t tap_bytes(const MapParams& p) { return 4 * stored_planes(p); }

}  // namespace
}  // namespace msm_filter

const MapFilterOps kMomentShadowMap = {
    "msm", "moment shadow map (Hamburger or Hausdorff 4MSM)", MapFilter::Moment,
    msm_filter::keys, msm_filter::filter, msm_filter::lookup,
    msm_filter::taps_per_lookup, msm_filter::tap_bytes, msm_filter::stored_planes,
    map_filter_always_by_tiles, false};

}  // namespace shadowlab
