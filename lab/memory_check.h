#pragma once
// The up-front memory check of the experiments: estimate what a run needs (GBuffer and its
// visibility buffer, masks and texel images, the reference, each technique's maps, the scene's
// geometry and BVH) and refuse it, before any work, when that exceeds the limit: --max-memory
// GB when given, else what the machine has available (MemAvailable of /proc/meminfo).
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

struct MemoryEstimate {
  uint64_t pixels_bytes = 0;  // GBuffer, visibility buffer, masks, texel images, reference
  uint64_t maps_bytes = 0;    // the largest technique's maps (techniques run one at a time)
  uint64_t scene_bytes = 0;   // geometry, transformed vertices, bins, BVH
  uint64_t total() const { return pixels_bytes + maps_bytes + scene_bytes; }
};

// specs must have been validated (their parse errors would name --technique).
MemoryEstimate estimate_run_memory(const Scene& scene, const std::vector<TechniqueSpec>& specs);
// Bytes available: MemAvailable from /proc/meminfo (0 when unknown).
uint64_t available_memory_bytes();
// Throws InputError("--max-memory" when max_bytes was given, else "--width", "needs about X GB
// (…), more than the Y GB …") when the estimate exceeds max_bytes (0: the memory available;
// unknown: no check). extra_image_bytes: images the experiment keeps beyond one run's (flicker's
// masks kept from frame to frame), counted with the image share.
void check_run_memory(const Scene& scene, const std::vector<TechniqueSpec>& specs,
                      uint64_t max_bytes, uint64_t extra_image_bytes = 0);

}  // namespace shadowlab
