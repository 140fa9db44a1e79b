// A demonstration filter ("hsm": chsm, thsm, phsm, dhsm): the nearest texel's stored distance
// against the receiver's; a shadowed receiver keeps `shade` of the light.
#include <algorithm>

#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"

namespace shadowlab {
namespace hsm_filter {
namespace {

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      {.name = "shade", .type = KeyType::Number, .def = 0.0, .lo = 0.0, .hi = 1.0,
       .help = "visibility of a shadowed receiver", .tune = "0|0.5",
       .store = [](MapParams& p, const KeyValue& v) { p.hsm.shade = v.number; }},
  };
  return k;
}

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    const LightFace& f = map.layout.faces[size_t(r.face)];
    const int x = std::clamp(int(r.st.x), 0, f.width - 1), y = std::clamp(int(r.st.y), 0, f.height - 1);
    const float d = map.dist.distance[size_t(r.face)][size_t(y) * size_t(f.width) + size_t(x)];
    return r.depth <= d ? 1.0f : float(p.hsm.shade);
  });
}

uint64_t taps_per_lookup(const MapParams&) { return 1; }
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 0; }

}  // namespace
}  // namespace hsm_filter

const MapFilterOps kHardMap = {
    "hsm", "hard shadow map (nearest texel)", MapFilter::Hard,
    hsm_filter::keys, hsm_filter::filter, hsm_filter::lookup,
    hsm_filter::taps_per_lookup, hsm_filter::tap_bytes, hsm_filter::stored_planes, nullptr, false};

}  // namespace shadowlab
