// The depth-compare filter ("sm": csm, tsm, psm): stored radial distance compared with the
// receiver's biased distance, one nearest texel (pcf=1) or N×N bilinear-weighted taps (PCF),
// with the seams of techniques/map_params.h (cross-face taps or a guard band).
#include <algorithm>

#include "core/error.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup.h"

namespace shadowlab {
namespace {

void parse_keys(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.pcf = r.get_int("pcf", p.pcf, 1, 15);
  if (p.pcf > 1 && p.pcf % 2 == 0)
    throw InputError(flag, name + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
  const std::string seams =
      r.get_choice("seams", p.seams == SeamMode::Cross ? "cross" : "guard", {"guard", "cross"});
  p.seams = seams == "cross" ? SeamMode::Cross : SeamMode::Guard;
}

std::string keys_text(const MapParams& p) {
  return std::string("pcf=1,seams=") + (p.seams == SeamMode::Cross ? "cross" : "guard");
}

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    // Lit weight over total weight: both sums see the same additions, so an all-lit
    // footprint gives exactly 1 whatever the float rounding of the weights.
    float lit = 0.0f, total = 0.0f;
    for_each_pcf_tap(L, r.face, r.st, p.pcf, [&](int f, int x, int y, float w) {
      const LightFace& lf = L.faces[size_t(f)];
      total += w;
      lit += r.depth <= map.dist.distance[size_t(f)][size_t(y) * size_t(lf.width) + size_t(x)] ? w : 0.0f;
    });
    return total > 0.0f ? std::min(lit / total, 1.0f) : 1.0f;
  });
}

uint64_t taps_per_lookup(const MapParams& p) {
  return p.pcf <= 1 ? 1 : uint64_t(p.pcf + 1) * uint64_t(p.pcf + 1);
}
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 0; }

}  // namespace

const MapFilterOps kDepthCompare = {"sm", "shadow map, depth compare with PCF", MapFilter::Depth,
                                    parse_keys, keys_text, filter, lookup, taps_per_lookup,
                                    tap_bytes, stored_planes};

}  // namespace shadowlab
