#include "lab/memory_check.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"

namespace shadowlab {
namespace {

// Bytes per camera pixel alive at once in the largest run: the GBuffer (position, geometric
// normal, depth, mesh and primitive ids, coverage: 37 B; the shading normal and uv are deferred,
// core/gbuffer_shading.h), the camera pass's
// visibility buffer (8 B), a technique's mask and texel image (8 B), the reference mask (4 B),
// the metric's double images (blurred masks and scratch, ~40 B in a sweep).
constexpr uint64_t kBytesPerPixel = 37 + 8 + 8 + 4 + 40;
// Bytes per triangle: positions, normals and indices, the transformed vertices and bins of a
// pass, Embree's BVH.
constexpr uint64_t kBytesPerTriangle = 400;

std::string gb(uint64_t bytes) {
  return bytes >= 1000000000ull ? fmt::format("{:.1f} GB", double(bytes) / 1e9)
                                : fmt::format("{:.0f} MB", double(bytes) / 1e6);
}

}  // namespace

MemoryEstimate estimate_run_memory(const Scene& scene, const std::vector<TechniqueSpec>& specs) {
  MemoryEstimate m;
  m.pixels_bytes = uint64_t(scene.camera.width) * uint64_t(scene.camera.height) * kBytesPerPixel;
  for (const TechniqueSpec& s : specs) m.maps_bytes = std::max(m.maps_bytes, technique_map_bytes(s, scene, "--technique"));
  m.scene_bytes = uint64_t(scene.triangle_count()) * kBytesPerTriangle;
  return m;
}

uint64_t available_memory_bytes() {
  std::ifstream f("/proc/meminfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("MemAvailable:", 0) == 0) {
      std::istringstream in(line.substr(13));
      uint64_t kb = 0;
      in >> kb;
      return kb * 1024;
    }
  return 0;
}

void check_run_memory(const Scene& scene, const std::vector<TechniqueSpec>& specs,
                      uint64_t max_bytes, uint64_t extra_image_bytes) {
  const bool given = max_bytes > 0;
  const char* flag = given ? "--max-memory" : "--width";
  const uint64_t limit = given ? max_bytes : available_memory_bytes();
  if (limit == 0) return;
  MemoryEstimate m = estimate_run_memory(scene, specs);
  m.pixels_bytes += extra_image_bytes;
  if (m.total() <= limit) return;
  throw InputError(flag, "this run needs about " + gb(m.total()) + " (image " + gb(m.pixels_bytes) +
                             ", maps " + gb(m.maps_bytes) + ", scene " + gb(m.scene_bytes) +
                             "), more than the " + gb(limit) +
                             (given ? " of --max-memory" : " this machine has available") +
                             "; lower --width/--height or the map resolution" +
                             (given ? "" : ", or give --max-memory GB to override"));
}

}  // namespace shadowlab
