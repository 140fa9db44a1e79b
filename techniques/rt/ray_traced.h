#pragma once
// The Embree ray tracer as a technique: the reference row of every sweep.
// Its keys (spp, hard, seed) are declared in ray_traced.cpp. A point light (radius 0) always gives the hard mask. Results are cached on disk when
// RunOptions::cache_dir is set (key: everything that determines the mask).
#include <vector>

#include "techniques/registry/technique.h"
#include "techniques/registry/technique_keys.h"

namespace shadowlab {

// Defaults, ranges and meanings: the declarations of ray_traced_keys().
struct RayTracedParams {
  int spp{};
  bool hard{};
  int seed{};
};
const std::vector<KeyDecl<RayTracedParams>>& ray_traced_keys();
RayTracedParams parse_ray_traced(const TechniqueSpec& spec, const char* flag);

// Computed once whatever options.repeats says: the reference is what the timed techniques are
// compared with, not a timed technique (its times are one run's).
ShadowResult run_ray_traced(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                            const RunOptions& options);

}  // namespace shadowlab
