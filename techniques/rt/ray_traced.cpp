#include "techniques/rt/ray_traced.h"

#include <chrono>
#include <cstdio>

#include "core/cache_file.h"

#include "core/rng.h"
#include "core/timer.h"
#include "raytrace/embree_scene.h"
#include "raytrace/reference_cache.h"
#include "raytrace/visibility.h"

namespace shadowlab {

const std::vector<KeyDecl<RayTracedParams>>& ray_traced_keys() {
  static const std::vector<KeyDecl<RayTracedParams>> k = {
      {.name = "spp", .type = KeyType::Integer, .def = 256, .lo = 1, .hi = 1 << 20,
       .help = "samples per pixel on the sphere light (stratified, per-pixel counter-based sequence)",
       .store = [](RayTracedParams& p, const KeyValue& v) { p.spp = int(v.number); }},
      {.name = "hard", .type = KeyType::Flag, .def = 0,
       .help = "1: treat the light as a point (one ray per pixel) whatever its radius",
       .store = [](RayTracedParams& p, const KeyValue& v) { p.hard = v.number != 0.0; }},
      {.name = "seed", .type = KeyType::Integer, .def = 1, .lo = 0, .hi = 1 << 30,
       .help = "sample-sequence seed (mixed with the scene seed)",
       .store = [](RayTracedParams& p, const KeyValue& v) { p.seed = int(v.number); }},
  };
  return k;
}

RayTracedParams parse_ray_traced(const TechniqueSpec& spec, const char* flag) {
  SpecReader r(spec, flag);
  RayTracedParams p;
  store_defaults(ray_traced_keys(), p);
  read_keys(r, spec.name, flag, ray_traced_keys(), p);
  r.reject_unknown();
  return p;
}

ShadowResult run_ray_traced(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                            const RunOptions& options) {
  const RayTracedParams p = parse_ray_traced(spec, options.flag);
  const int spp = p.spp;
  const bool hard = p.hard || scene.light.radius <= 0.0f;
  const uint64_t seed = mix64(scene.seed) ^ uint64_t(p.seed);

  ShadowResult res;
  // The hard mask is keyed as spp 0 so it never collides with a soft one.
  const int key_spp = hard ? 0 : spp;
  std::string key = options.cache_dir.empty() ? "" : reference_key(scene, gbuffer, key_spp, seed);
  if (!key.empty() && load_cached_reference(options.cache_dir, key, res.mask) &&
      res.mask.width == gbuffer.width && res.mask.height == gbuffer.height) {
    res.from_cache = true;
    res.notes = "reference from cache " + cached_reference_path(options.cache_dir, key);
    return res;
  }
  // A cache folder that cannot take the result is found out before the work, not after it: the
  // reference is then computed and used but not cached (a warning says so).
  std::string why;
  if (!key.empty() && !folder_is_writable(options.cache_dir, why)) {
    std::fprintf(stderr, "warning: reference cache folder %s is not writable (%s): the reference is not cached\n",
                 options.cache_dir.c_str(), why.c_str());
    key.clear();
  }
  auto t0 = std::chrono::steady_clock::now();
  EmbreeScene rt(scene);
  res.map_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  if (hard) {
    res.mask = hard_visibility(rt, scene, gbuffer);
  } else {
    ProgressLine line("reference " + std::to_string(spp) + " spp",
                      visibility_work_units(gbuffer.width, gbuffer.height), options.progress);
    res.mask = soft_visibility(rt, scene, gbuffer, spp, seed, &line);
  }
  res.lookup_ms = ms_since(t0);
  // Never lose computed work: a write that fails anyway (a full disk) is a warning.
  if (!key.empty()) {
    try {
      store_cached_reference(options.cache_dir, key, res.mask);
    } catch (const InputError& e) {
      std::fprintf(stderr, "warning: reference not cached: %s\n", e.what());
    }
  }
  res.notes = hard ? "hard shadows, 1 ray per pixel"
                   : std::to_string(spp) + " rays per pixel on a sphere light of radius " +
                         std::to_string(scene.light.radius) + " m";
  return res;
}

}  // namespace shadowlab
