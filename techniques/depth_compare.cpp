// The depth-compare filter ("sm": csm, tsm, psm): stored radial distance compared with the
// receiver's biased distance, one nearest texel (pcf=1), N×N bilinear-weighted taps (PCF), or
// rotated Poisson-disk taps (pcf_kind=poisson), with the seams of techniques/map_params.h
// (cross-face taps or a guard band).
#include <algorithm>

#include "core/error.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup.h"
#include "techniques/poisson_disk.h"

namespace shadowlab {
namespace {

void parse_keys(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.pcf = r.get_int("pcf", p.pcf, 1, 15);
  if (p.pcf > 1 && p.pcf % 2 == 0)
    throw InputError(flag, name + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
  const bool poisson = r.get_choice("pcf_kind", "grid", {"grid", "poisson"}) == "poisson";
  if (poisson) {
    p.pcf_kind = PcfKind::Poisson;
    p.taps = r.get_int("taps", p.taps, 4, 64);
    if (p.pcf < 3)
      throw InputError(flag, name + ": 'pcf_kind=poisson' needs pcf >= 3 (the disk's diameter in texels)");
  }
  // Poisson taps rotate freely, so they read through the guard band (the cube's cross-face
  // lookup serves the grid's texel rows).
  // rpdb's plane gradient lives in the receiver's own face: it takes the guard band too.
  read_rpdb(r, name, flag, p);
  const std::string seams =
      r.get_choice("seams", p.seams == SeamMode::Cross && !poisson && !p.rpdb ? "cross" : "guard",
                   {"guard", "cross"});
  if (poisson && seams == "cross")
    throw InputError(flag, name + ": 'seams=cross' serves the grid PCF only; Poisson taps use the guard band");
  if (p.rpdb && seams == "cross")
    throw InputError(flag, name + ": 'rpdb=1' needs the guard band ('seams=guard'): the plane "
                                  "gradient is in the receiver's own face");
  p.seams = seams == "cross" ? SeamMode::Cross : SeamMode::Guard;
}

std::string keys_text(const MapParams& p) {
  return std::string("pcf=1,seams=") + (p.seams == SeamMode::Cross ? "cross" : "guard") +
         ",pcf_kind=grid,taps=" + std::to_string(p.taps) + ",rpdb=0";
}

// Rotated Poisson PCF at receiver r: taps at st + (pcf/2)·R(θ)·q_k, θ from the pixel's counter-
// based random number, each a bilinear-weighted compare of its 2×2 texels (clamped to the face;
// the guard band keeps them inside its image). Returns the lit fraction.
float poisson_visibility(const LightFace& f, const float* dist, const Receiver& r,
                         const PoissonDisk& disk, float radius) {
  const vec2 rot = poisson_rotation(r.pixel);
  const float c = rot.x, s = rot.y;
  float lit = 0.0f;
  for (const vec2& q : disk.points) {
    const vec2 st(r.st.x + radius * (c * q.x - s * q.y), r.st.y + radius * (s * q.x + c * q.y));
    const Bilinear b = bilinear_taps(st, f.width, f.height);
    // rpdb: the receiver plane's depth at each texel's centre (grad is 0 without it).
    auto at = [&](int x, int y) {
      const float depth = r.depth + glm::dot(r.grad, vec2(float(x) + 0.5f, float(y) + 0.5f) - r.st);
      return depth <= dist[size_t(y) * size_t(f.width) + size_t(x)] ? 1.0f : 0.0f;
    };
    lit += (1.0f - b.fy) * ((1.0f - b.fx) * at(b.x0, b.y0) + b.fx * at(b.x1, b.y0)) +
           b.fy * ((1.0f - b.fx) * at(b.x0, b.y1) + b.fx * at(b.x1, b.y1));
  }
  return lit / float(disk.points.size());
}

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  if (p.pcf_kind == PcfKind::Poisson) {
    const PoissonDisk disk = poisson_disk(p.taps);
    const float radius = 0.5f * float(p.pcf);
    lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
      return poisson_visibility(L.faces[size_t(r.face)], map.dist.distance[size_t(r.face)].data(),
                                r, disk, radius);
    });
    return;
  }
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    // Lit weight over total weight: both sums see the same additions, so an all-lit
    // footprint gives exactly 1 whatever the float rounding of the weights.
    float lit = 0.0f, total = 0.0f;
    for_each_pcf_tap(L, r.face, r.st, p.pcf, [&](int f, int x, int y, float w) {
      const LightFace& lf = L.faces[size_t(f)];
      total += w;
      // rpdb (guard band: every tap in the receiver's face): the receiver plane's depth at the
      // texel centre; grad is 0 without it.
      const float depth = r.depth + glm::dot(r.grad, vec2(float(x) + 0.5f, float(y) + 0.5f) - r.st);
      lit += depth <= map.dist.distance[size_t(f)][size_t(y) * size_t(lf.width) + size_t(x)] ? w : 0.0f;
    });
    return total > 0.0f ? std::min(lit / total, 1.0f) : 1.0f;
  });
}

uint64_t taps_per_lookup(const MapParams& p) {
  if (p.pcf_kind == PcfKind::Poisson) return 4 * uint64_t(p.taps);  // 2×2 texels per tap
  return p.pcf <= 1 ? 1 : uint64_t(p.pcf + 1) * uint64_t(p.pcf + 1);
}
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 0; }

}  // namespace

const MapFilterOps kDepthCompare = {"sm", "shadow map, depth compare with PCF", MapFilter::Depth,
                                    parse_keys, keys_text, filter, lookup, taps_per_lookup,
                                    tap_bytes, stored_planes};

}  // namespace shadowlab
