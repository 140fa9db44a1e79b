#pragma once
// GBuffer: what the camera pass leaves per pixel, the common input of every technique and of
// the Embree reference (both evaluate visibility at these same surface points).
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace shadowlab {

constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

struct GBuffer {
  int width = 0;
  int height = 0;
  // Per pixel, row-major (index y * width + x). Valid only where covered != 0.
  std::vector<vec3> position;        // world space, metres (interpolated, perspective-correct)
  std::vector<vec3> normal;          // shading normal, world space, unit length
  std::vector<vec3> geo_normal;      // geometric normal of the triangle, world space, unit
  std::vector<vec2> uv;              // texture coordinates (0 when the mesh has none)
  std::vector<float> depth;          // view-space distance along -z, metres (+inf where empty)
  std::vector<uint32_t> mesh_id;     // index into Scene::meshes, kNoPrimitive where empty
  std::vector<uint32_t> prim_id;     // triangle index within that mesh, kNoPrimitive where empty
  std::vector<uint8_t> covered;      // 1 where some triangle covers the pixel centre

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  // Sizes every array and resets it to the empty values (covered 0, ids kNoPrimitive, ...).
  void resize(int w, int h);
  // Sizes every array keeping whatever values are there (for writers that set every pixel).
  void reshape(int w, int h);
};

}  // namespace shadowlab
