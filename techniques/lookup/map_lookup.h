#pragma once
// The lookup loop every filter of the light-map pipeline runs (techniques/pipeline/map_filter.h): the
// AVX2 receiver kernels in front where they apply (techniques/lookup/map_lookup_simd.h), the scalar
// pixel loop (their oracle, techniques/lookup/map_receiver.h) for the rest.
#include <algorithm>

#include "techniques/pipeline/light_map.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {

// The receiver of lane k of a SIMD group.
inline Receiver lane_receiver(const Receivers8& r, int k, size_t pixel) {
  Receiver rc;
  rc.pixel = pixel;
  rc.face = r.face[k];
  rc.st = vec2(r.sx[k], r.sy[k]);
  rc.depth = r.depth[k];
  rc.texel = uint32_t(r.texel[k]);
  return rc;
}

// No batch form: lanes of a SIMD group run `visibility` one by one.
struct NoBatch {
  static constexpr bool kEnabled = false;
  void operator()(const MapLookupConsts&, const Receivers8&, size_t, float*) const {}
  void prefetch(const MapLookupConsts&, const Receivers8&) const {}
};

// One call of a batch on G groups: batch(consts, receivers, first_pixel, out) for G = 1,
// batch.groups(consts, receivers, out) for more (the batch's type a template parameter, so the
// branch not taken is not instantiated).
template <int G, class Batch>
inline void call_batch(const Batch& batch, const MapLookupConsts& c, const Receivers8* r,
                       size_t first, float (*out)[8]) {
  if constexpr (G == 1)
    batch(c, r[0], first, out[0]);
  else
    batch.groups(c, r, out);
}

// Runs `visibility(receiver)` for every looked-up pixel: with no normal offset, the receivers
// of 8 pixels at a time come from the AVX2 kernel, and depth compare runs its one-tap or N×N
// compare in vector form too (footprints inside a face); the scalar loop takes the rest.
// `batch(consts, receivers, first_pixel, out)`, when given (kEnabled), computes the 8 lanes'
// visibility at once (the filters' AVX2 kernels; lane k is GBuffer pixel first_pixel + k); it
// must give `visibility`'s bits lane for lane (its oracle).
template <class Visibility, class Batch = NoBatch>
void lookup_pixels(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
                   ImageF& mask, ImageU32* texels, const Visibility& visibility,
                   const Batch& batch = Batch{}) {
  const FaceLayout& L = map.layout;
  // The AVX2 receivers carry no plane gradient: rpdb takes the scalar loop, unless the batch
  // computes each lane's gradient itself (Batch::kComputesGradient) and takes every lane.
  constexpr bool batch_gradient = [] {
    if constexpr (requires { Batch::kComputesGradient; }) return Batch::kComputesGradient;
    return false;
  }();
  const LookupKernels& kernels = lookup_kernels(process_isa());
  const Receivers8Fn receivers8 =
      p.normal <= 0.0f && (!p.rpdb || batch_gradient) ? kernels.receivers8 : nullptr;
  if (!receivers8) {
    lookup_faces(scene, g, L, p, mask, texels, visibility, [](size_t, size_t) { return size_t(0); });
    return;
  }
  const MapLookupConsts c = map_lookup_consts(scene, L, p, map.dist.distance);
  const bool depth = p.filter == MapFilter::Depth && c.gather_ok;
  const Depth1Fn depth1 = depth && p.pcf <= 1 ? kernels.depth1 : nullptr;
  const PcfFn pcf = depth && p.pcf > 1 && p.pcf_kind == PcfKind::Grid ? kernels.pcf : nullptr;
  lookup_faces(scene, g, L, p, mask, texels, visibility, [&](size_t b, size_t e) {
    size_t i = b;
    // The batch's pixels, G groups of 8 per call, from i on while G groups remain (returns the
    // first pixel not done): the next call's receivers computed and their map rows prefetched
    // (Batch::prefetch) ahead, so the current reconstruction overlaps the next one's memory
    // reads; the inactive lanes' masks merged in one vector step. G = 1 calls
    // batch(consts, receivers, first_pixel, out); G > 1 batch.groups(consts, receivers, out).
    auto run_batches = [&]<int G>(size_t from) {
      constexpr size_t span = 8 * size_t(G);
      auto group = [&](size_t at, Receivers8& r) {
        receivers8(c, &g.position[at].x, &g.geo_normal[at].x, &g.covered[at], r);
      };
      Receivers8 cur[G], ahead[G];
      bool have_ahead = false;
      size_t at = from;
      for (; at + span <= e; at += span) {
        for (int h = 0; h < G; ++h) {
          if (have_ahead)
            cur[h] = ahead[h];
          else
            group(at + 8 * size_t(h), cur[h]);
        }
        have_ahead = at + 2 * span <= e;
        if (have_ahead)
          for (int h = 0; h < G; ++h) {
            group(at + span + 8 * size_t(h), ahead[h]);
            batch.prefetch(c, ahead[h]);
          }
        alignas(32) float vis[G][8];
        call_batch<G>(batch, c, cur, at, vis);
        for (int h = 0; h < G; ++h) {
          const size_t px = at + 8 * size_t(h);
          kernels.merge8(cur[h], vis[h], &mask.data[px], texels ? &texels->data[px] : nullptr);
        }
      }
      return at;
    };
    if constexpr (Batch::kEnabled) {
      if (!depth1 && !pcf) {
        // A batch that takes several groups at a time (Batch::kGroups, when its grouped()
        // says so) gets them, then single groups for what is left.
        if constexpr (requires { Batch::kGroups; })
          if (batch.grouped()) i = run_batches.template operator()<Batch::kGroups>(i);
        i = run_batches.template operator()<1>(i);
      }
    }
    for (; i + 8 <= e; i += 8) {
      const float* pos = &g.position[i].x;
      const float* nrm = &g.geo_normal[i].x;
      float* m = &mask.data[i];
      uint32_t* t = texels ? &texels->data[i] : nullptr;
      if (depth1) {
        depth1(c, pos, nrm, &g.covered[i], m, t);
        continue;
      }
      Receivers8 r;
      if (pcf) {
        pcf(c, p.pcf, pos, nrm, &g.covered[i], m, t, r);
      } else {
        receivers8(c, pos, nrm, &g.covered[i], r);
        for (int k = 0; k < 8; ++k) {
          m[k] = r.mask[k];
          if (t) t[k] = uint32_t(r.texel[k]);
        }
      }
      for (int k = 0; k < 8; ++k) {
        if (!r.active[k]) continue;
        const Receiver rc = lane_receiver(r, k, i + size_t(k));
        m[k] = std::clamp(visibility(rc), 0.0f, 1.0f);
        if (t) t[k] = rc.texel;
      }
    }
    return i - b;
  });
}

}  // namespace shadowlab
