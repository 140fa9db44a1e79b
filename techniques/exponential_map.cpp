// The exponential filter ("esm": cesm, tesm, pesm): the occluder term exp(c·z) box-filtered in
// log space (techniques/moment_filter.h), looked up bilinearly as Σ w·exp(c·z_occ − c·t).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup.h"

namespace shadowlab {
namespace {

void parse_keys(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.blur = r.get_int("blur", p.blur, 1, 63);
  if (p.blur % 2 == 0)
    throw InputError(flag, name + ": 'blur' must be odd, got " + std::to_string(p.blur));
  // exp(c·Δ) with Δ <= 1 must stay below DBL_MAX (ln ≈ 709.8) in the filter; see moment_filter.h.
  p.esm.c = r.get_double("c", p.esm.c, 0.01, 700.0);
}

std::string keys_text(const MapParams& p) {
  char b[64];
  std::snprintf(b, sizeof b, "blur=%d,c=%g", p.blur, p.esm.c);
  return b;
}

void filter(const MapParams& p, LightMap& map) {
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    filter_esm_log(map.dist.distance[f].data(), face.width, face.height, p.blur, p.esm.c, map.a[f],
                   map.scratch);
  }
}

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double c = p.esm.c;
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    const LightFace& f = L.faces[size_t(r.face)];
    const float* z = map.a[size_t(r.face)].data();
    const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
    const float ct = float(c) * r.depth;
    // Σ w·exp(c·z_occ − c·t): the bilinear filter of exp(c·z) times exp(−c·t). Each exponent
    // is capped at 80 (e^80 ≈ 5.5e34, so four terms stay finite in float): any such tap already
    // makes the sum >= 1 unless its weight is below e^-80, and the result is clamped to 1.
    auto term = [&](int x, int y) {
      return std::exp(std::min(z[size_t(y) * size_t(f.width) + size_t(x)] - ct, 80.0f));
    };
    const float v = (1.0f - bl.fy) * ((1.0f - bl.fx) * term(bl.x0, bl.y0) + bl.fx * term(bl.x1, bl.y0)) +
                    bl.fy * ((1.0f - bl.fx) * term(bl.x0, bl.y1) + bl.fx * term(bl.x1, bl.y1));
    return std::min(v, 1.0f);
  });
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 1; }

}  // namespace

const MapFilterOps kExponentialMap = {"esm", "exponential shadow map", MapFilter::Exponential,
                                      parse_keys, keys_text, filter, lookup, taps_per_lookup,
                                      tap_bytes, stored_planes};

}  // namespace shadowlab
