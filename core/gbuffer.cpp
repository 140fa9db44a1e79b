#include "core/gbuffer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowlab {

void GBuffer::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = pixel_count();
  position.assign(n, vec3(0.0f));
  normal.assign(n, vec3(0.0f));
  geo_normal.assign(n, vec3(0.0f));
  uv.assign(n, vec2(0.0f));
  depth.assign(n, std::numeric_limits<float>::infinity());
  mesh_id.assign(n, kNoPrimitive);
  prim_id.assign(n, kNoPrimitive);
  covered.assign(n, 0);
  block_bounds.clear();
}

void GBuffer::reshape(int w, int h) {
  width = w;
  height = h;
  const size_t n = pixel_count();
  position.resize(n);
  normal.clear();  // deferred: core/gbuffer_shading.h
  geo_normal.resize(n);
  uv.clear();
  depth.resize(n);
  mesh_id.resize(n);
  prim_id.resize(n);
  covered.resize(n);
  block_bounds.clear();
}

}  // namespace shadowlab
