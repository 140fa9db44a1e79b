// The depth-compare filter ("sm": csm, tsm, psm): stored radial distance compared with the
// receiver's biased distance, one nearest texel (pcf=1), N×N bilinear-weighted taps (PCF), or
// rotated Poisson-disk taps (pcf_kind=poisson), with the seams of techniques/pipeline/map_params.h
// (cross-face taps or a guard band).
#include <algorithm>

#include "core/error.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"
#include "techniques/lookup/poisson_disk.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace sm_filter {
namespace {

// Poisson taps rotate freely, so they read through the guard band (the cube's cross-face lookup
// serves the grid's texel rows); rpdb's plane gradient lives in the receiver's own face: it
// takes the guard band too. Without seams given, both switch the cube's default to the guard.
void check_seams(const KeyCheck& c, MapParams& p) {
  const bool poisson = p.pcf_kind == PcfKind::Poisson;
  if (!c.value.given && (poisson || p.rpdb)) p.seams = SeamMode::Guard;
  if (poisson && p.seams == SeamMode::Cross)
    throw InputError(c.flag, c.name + ": 'seams=cross' serves the grid PCF only; Poisson taps use the guard band");
  if (p.rpdb && p.seams == SeamMode::Cross)
    throw InputError(c.flag, c.name + ": 'rpdb=1' needs the guard band ('seams=guard'): the plane "
                                      "gradient is in the receiver's own face");
}

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      {.name = "pcf", .type = KeyType::Integer, .def = 1, .lo = 1, .hi = 15,
       .help = "1: the nearest texel; odd N >= 3: N×N bilinear-weighted taps (grid) or the "
               "diameter in texels of the Poisson disk",
       .tune = "1|3|5",
       .store = [](MapParams& p, const KeyValue& v) { p.pcf = int(v.number); },
       .check = [](const KeyCheck& c, MapParams& p) {
         if (p.pcf > 1 && p.pcf % 2 == 0)
           throw InputError(c.flag, c.name + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
       }},
      {.name = "pcf_kind", .type = KeyType::Choice, .def_word = "grid", .choices = "grid|poisson",
       .help = "the PCF footprint: the N×N grid, or Poisson-disk taps rotated per pixel (needs pcf >= 3)",
       .store = [](MapParams& p, const KeyValue& v) {
         p.pcf_kind = v.word == "poisson" ? PcfKind::Poisson : PcfKind::Grid;
       }},
      {.name = "taps", .type = KeyType::Integer, .def = 16, .lo = 4, .hi = 64,
       .help = "Poisson taps per pixel", .needs = "pcf_kind=poisson",
       .store = [](MapParams& p, const KeyValue& v) { p.taps = int(v.number); },
       .check = [](const KeyCheck& c, MapParams& p) {
         if (p.pcf < 3)
           throw InputError(c.flag, c.name + ": 'pcf_kind=poisson' needs pcf >= 3 (the disk's diameter in texels)");
       }},
      map_rpdb_key(),
      {.name = "seams", .type = KeyType::Choice, .def_word = "guard", .choices = "guard|cross",
       .help = "taps beyond a face's image: read in a guard band rendered around each face, or "
               "looked up through their direction in the neighbouring face (grid PCF without rpdb)",
       .store = [](MapParams& p, const KeyValue& v) {
         p.seams = v.word == "cross" ? SeamMode::Cross : SeamMode::Guard;
       },
       .check = check_seams},
  };
  return k;
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

// 8 lanes of rotated Poisson PCF at once (the lookup batch table's poisson_batch: the operations
// of poisson_visibility without rpdb, in its order), with each lane's rotation from its pixel.
// Used only where the AVX2 kernels and one-base gathers exist.
struct PoissonBatch {
  static constexpr bool kEnabled = true;
  void prefetch(const MapLookupConsts&, const Receivers8&) const {}  // taps spread over a disk
  const PoissonDisk* disk;
  float radius;
  const LightMap* map;
  PoissonBatchFn kernel;
  void operator()(const MapLookupConsts& c, const Receivers8& r, size_t first, float* out) const {
    if (!c.gather_ok) {  // faces too far apart for one gather base: the scalar taps, lane by lane
      for (int k = 0; k < 8; ++k) {
        if (!r.active[k]) continue;
        const Receiver rc = lane_receiver(r, k, first + size_t(k));
        const size_t f = size_t(rc.face);
        out[k] = poisson_visibility(map->layout.faces[f], map->dist.distance[f].data(), rc, *disk,
                                    radius);
      }
      return;
    }
    float cosv[8], sinv[8];
    for (int k = 0; k < 8; ++k) {
      const vec2 rot = r.active[k] ? poisson_rotation(first + size_t(k)) : vec2(1.0f, 0.0f);
      cosv[k] = rot.x;
      sinv[k] = rot.y;
    }
    kernel(c, r, cosv, sinv, disk->points.data(), int(disk->points.size()), radius, out);
  }
};

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  if (p.pcf_kind == PcfKind::Poisson) {
    const PoissonDisk disk = poisson_disk(p.taps);
    const float radius = 0.5f * float(p.pcf);
    auto visibility = [&](const Receiver& r) {
      return poisson_visibility(L.faces[size_t(r.face)], map.dist.distance[size_t(r.face)].data(),
                                r, disk, radius);
    };
    // The batch needs AVX2 (the scalar tables' receivers8 and poisson_batch are null) and no
    // plane gradient.
    const PoissonBatchFn kernel = lookup_batch_kernels(process_isa()).poisson_batch;
    if (lookup_kernels(process_isa()).receivers8 && kernel && !p.rpdb)
      lookup_pixels(scene, g, p, map, mask, texels, visibility,
                    PoissonBatch{&disk, radius, &map, kernel});
    else
      lookup_pixels(scene, g, p, map, mask, texels, visibility);
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
}  // namespace sm_filter

const MapFilterOps kDepthCompare = {
    "sm", "shadow map, depth compare with PCF", MapFilter::Depth,
    sm_filter::keys, sm_filter::filter, sm_filter::lookup,
    sm_filter::taps_per_lookup, sm_filter::tap_bytes, sm_filter::stored_planes, nullptr, false};

}  // namespace shadowlab
