#pragma once
// AVX2 path of the light-map depth lookup with pcf=1 and no normal offset on the tetrahedral and
// projector layouts, 8 pixels at a time (the cube layout without a guard band has its own kernel,
// techniques/cube_lookup_simd.h). It performs the same IEEE operations in the same order as
// make_receiver() and the one-tap compare of techniques/light_map.cpp (its oracle), so masks and
// texel indices are bit-identical; tests compare whole renders with SHADOWLAB_SCALAR=1 (which
// disables this path) against the default.
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/scene.h"
#include "techniques/light_faces.h"
#include "techniques/map_params.h"

namespace shadowlab {

// Per-face constants in lanes 0..3 (one face per lane, at most 4 faces), plus the scalars.
struct MapLookupConsts {
  vec3 light{0.0f};
  float inv_far = 0.0f;
  float bias = 0.0f;             // constant bias, metres
  float slope_k = 0.0f;          // slope × reach (make_receiver's k)
  float plane_texel = 0.0f;      // face 0's plane texel size
  bool tetra = false;            // faces by argmax of the tetrahedron's normals; else one face
  bool projector = false;        // gate by the projector's frustum
  vec3 proj_forward{0.0f}, proj_right{0.0f}, proj_up{0.0f};
  float proj_tan_x = 0.0f, proj_tan_y = 0.0f;
  alignas(32) float fwd[3][8] = {}, right[3][8] = {}, up[3][8] = {};
  alignas(32) float left[8] = {}, range_u[8] = {}, top[8] = {}, range_v[8] = {};
  alignas(32) float width_f[8] = {}, height_f[8] = {};
  alignas(32) int32_t width[8] = {}, height[8] = {}, base[8] = {};
  const float* depth[4] = {};    // rendered faces (nullptr where a face was not rendered)
};

MapLookupConsts map_lookup_consts(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                                  const std::vector<std::vector<float>>& face_depth);

using MapLookup8Fn = void (*)(const MapLookupConsts& c, const float* pos, const float* nrm,
                              const uint8_t* covered, float* mask, uint32_t* texels);

// The AVX2 path, or nullptr when the CPU lacks AVX2 or SHADOWLAB_SCALAR=1.
MapLookup8Fn map_lookup8_simd();

}  // namespace shadowlab
