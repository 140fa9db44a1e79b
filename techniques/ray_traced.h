#pragma once
// The Embree ray tracer as a technique: the reference row of every sweep.
// Spec: rt:spp=256,hard=0,seed=1
//   spp   samples per pixel on the sphere light (stratified, per-pixel counter-based sequence)
//   hard  1 = treat the light as a point (one ray per pixel) whatever its radius
//   seed  sample-sequence seed (mixed with the scene seed)
// A point light (radius 0) always gives the hard mask. Results are cached on disk when
// RunOptions::cache_dir is set (key: everything that determines the mask).
#include "techniques/technique.h"

namespace shadowlab {

struct RayTracedParams {
  int spp = 256;
  bool hard = false;
  int seed = 1;
};
RayTracedParams parse_ray_traced(const TechniqueSpec& spec, const char* flag);

// Computed once whatever options.repeats says: the reference is what the timed techniques are
// compared with, not a timed technique (its times are one run's).
ShadowResult run_ray_traced(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                            const RunOptions& options);

}  // namespace shadowlab
