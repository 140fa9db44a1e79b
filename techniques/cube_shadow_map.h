#pragma once
// Cube shadow map (CSM) for a point light: six 90° faces storing the radial distance to the
// light, normalised by the light range (|p - L| / far; +inf where a texel saw nothing).
// Spec: csm:res=512,pcf=1,bias=0.01,slope=1
//   res    face edge in texels
//   pcf    1 = one nearest-texel comparison (hard); odd N >= 3 = N×N comparisons, each
//          bilinear-weighted (an (N+1)² texel footprint); taps leaving a face are looked up in
//          the neighbouring face through their direction (no seams)
//   bias   constant depth bias, metres
//   slope  slope-scaled bias: slope × texel size at the receiver × tan(angle to light)
//          (tan clamped to 10, i.e. N·L >= 0.1) × (pcf + 1)/2 (the filter's reach in texels), metres
//   normal normal-offset bias: the lookup point moves along the geometric normal by
//          normal × texel size at the receiver × (1 - N·L) (techniques/normal_offset.h); 0 = off
//   depth  stored precision: f32 (default), 16, 8, 8cubic (techniques/depth_quantize.h)
#include <array>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "raster/raster_types.h"
#include "techniques/cube_faces.h"
#include "techniques/depth_quantize.h"
#include "techniques/technique.h"

namespace shadowlab {

struct CubeShadowParams {
  int res = 512;
  int pcf = 1;
  float bias = 0.01f;
  float slope = 1.0f;
  float normal = 0.0f;
  DepthFormat depth = DepthFormat::F32;
};

CubeShadowParams parse_cube_params(const TechniqueSpec& spec, const char* flag);

struct CubeShadowMap {
  int res = 0;
  std::array<std::vector<float>, kCubeFaces> depth;  // res² per rendered face, row-major, y down
  std::array<mat4, kCubeFaces> view_proj;
  std::array<bool, kCubeFaces> rendered{};
};

// Faces that the lookups of the covered, light-facing GBuffer pixels touch (taps included).
std::array<bool, kCubeFaces> cube_faces_needed(const Scene& scene, const GBuffer& g,
                                               const CubeShadowParams& p);
// Renders the needed faces (depth only) and converts them to normalised radial distance.
// Faces are rendered with no face culling unless `cull` says otherwise (benchmarks).
void render_cube_map(const Scene& scene, const std::array<bool, kCubeFaces>& needed, int res,
                     CubeShadowMap& map, size_t* submitted = nullptr, size_t* culled = nullptr,
                     CullMode cull = CullMode::None);
// Looks up every GBuffer pixel: mask and (optionally) texel index.
void lookup_cube_map(const Scene& scene, const GBuffer& g, const CubeShadowMap& map,
                     const CubeShadowParams& p, ImageF& mask, ImageU32* texels);

ShadowResult run_cube_shadow_map(const TechniqueSpec& spec, const Scene& scene,
                                 const GBuffer& gbuffer, const RunOptions& options);

}  // namespace shadowlab
