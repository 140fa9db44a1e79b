#include "techniques/ray_traced.h"

#include <chrono>

#include "core/rng.h"
#include "core/timer.h"
#include "raytrace/embree_scene.h"
#include "raytrace/reference_cache.h"
#include "raytrace/visibility.h"

namespace shadowlab {

ShadowResult run_ray_traced(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                            const RunOptions& options) {
  SpecReader r(spec, options.flag);
  const int spp = r.get_int("spp", 256, 1, 1 << 20);
  const bool hard = r.get_bool("hard", false) || scene.light.radius <= 0.0f;
  const uint64_t seed = mix64(scene.seed) ^ uint64_t(r.get_int("seed", 1, 0, 1 << 30));
  r.reject_unknown();

  ShadowResult res;
  // The hard mask is keyed as spp 0 so it never collides with a soft one.
  const int key_spp = hard ? 0 : spp;
  const std::string key = options.cache_dir.empty() ? "" : reference_key(scene, gbuffer, key_spp, seed);
  if (!key.empty() && load_cached_reference(options.cache_dir, key, res.mask) &&
      res.mask.width == gbuffer.width && res.mask.height == gbuffer.height) {
    res.from_cache = true;
    res.notes = "reference from cache " + cached_reference_path(options.cache_dir, key);
    return res;
  }
  std::vector<double> build_t, trace_t;
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    EmbreeScene rt(scene);
    build_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    if (hard) {
      res.mask = hard_visibility(rt, scene, gbuffer);
    } else {
      ProgressLine line("reference " + std::to_string(spp) + " spp",
                        visibility_work_units(gbuffer.width, gbuffer.height), options.progress);
      res.mask = soft_visibility(rt, scene, gbuffer, spp, seed, &line);
    }
    trace_t.push_back(ms_since(t0));
  }
  res.map_ms = median(build_t);
  res.lookup_ms = median(trace_t);
  if (!key.empty()) store_cached_reference(options.cache_dir, key, res.mask);
  res.notes = hard ? "hard shadows, 1 ray per pixel"
                   : std::to_string(spp) + " rays per pixel on a sphere light of radius " +
                         std::to_string(scene.light.radius) + " m";
  return res;
}

}  // namespace shadowlab
