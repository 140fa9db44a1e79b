#pragma once
// AVX2 path of the cube-map lookup with pcf=1, 8 pixels at a time. It performs the same IEEE
// operations in the same order as the scalar lookup in cube_shadow_map.cpp (its oracle), so
// masks and texel indices are bit-identical; tests compare whole renders with
// SHADOWLAB_SCALAR=1 (which disables this path) against the default.
#include <cstdint>

#include "core/math.h"

namespace shadowlab {

struct CubeLookupConsts {
  vec3 light;                  // light position, world space
  float inv_far;               // 1 / light range
  float bias;                  // constant bias, metres
  float slope_k;               // (slope · footprint) · texel_angle, as the scalar path groups it
  int res;                     // face edge in texels
  const float* face_depth[6];  // rendered faces (nullptr where a face was not rendered)
};

// Looks up pixels [0, 8) of the given GBuffer rows: pos and nrm point at 8 packed vec3
// (x, y, z floats), covered at 8 flags. Writes 8 mask values and, when texels is not null,
// 8 texel indices.
using CubeLookup8Fn = void (*)(const CubeLookupConsts& c, const float* pos, const float* nrm,
                               const uint8_t* covered, float* mask, uint32_t* texels);

// The AVX2 path, or nullptr when the CPU lacks AVX2 or SHADOWLAB_SCALAR=1.
CubeLookup8Fn cube_lookup8_simd();

}  // namespace shadowlab
