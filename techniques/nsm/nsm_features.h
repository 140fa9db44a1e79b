#pragma once
// The per-pixel input features of Neural Shadow Mapping (docs/techniques/nsm.md "Features"):
// planar fp32 images over a GBuffer, computed from the scene's light and camera, the GBuffer and
// one plain base map (the cube layout's radial depth map, `csm` with no PCF and no bias). Every
// length is divided by the scene scale s = |L − camera target| / kNsmScaleRef.
//   d           view-space depth / s
//   z           the base map's nearest texel along p − L (radial distance / s; empty: far / s)
//   z_f         |p − L| / s
//   c_e         n·(L − p)/|L − p|, n the geometric normal facing the eye
//   c_c         n·(eye − p)/|eye − p|
//   n_x,n_y,n_z the geometric normal in view space
//   z_minus_zf  z − z_f (of the fp32 planes above)
//   z_over_zf   z / z_f
//   cc_over_d   c_c / d
//   c_e_r       c_e + r_e, r_e = 4·R/R_max (R the light radius in metres, before /s)
// Uncovered pixels: every feature 0 and coverage 0.
#include <cstdint>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "techniques/pipeline/light_map.h"

namespace shadowlab {

constexpr float kNsmScaleRef = 3.12f;  // m: |L − target| of the default scene
constexpr float kNsmRadiusMax = 0.3f;  // m: the light radius whose size code r_e is 4

// Every candidate feature, in the order of the table above.
const std::vector<std::string>& nsm_feature_names();
// The network's default input, in its order: z_over_zf, z_minus_zf, c_e_r, d.
const std::vector<std::string>& nsm_network_features();
// True when `name` is one of nsm_feature_names().
bool is_nsm_feature(const std::string& name);

// s = |L − camera.target| / kNsmScaleRef.
float nsm_scene_scale(const Scene& scene);
// r_e = 4·R/kNsmRadiusMax.
float nsm_size_code(float radius);

// The base map's parameters: csm (or the depth-compare map of another layout) at resolution
// `res`, fp32 depths, nearest texel (pcf=1), no constant, slope or normal-offset bias. Every
// layout stores the same radial distance; only the texels' sizes and shapes differ.
MapParams nsm_base_map_params(int res, FaceLayoutKind layout = FaceLayoutKind::Cube);
// The base map's faces some covered pixel of `g` reads (its face along p − L, whether the pixel
// faces the light or not: every covered pixel has a z).
std::vector<bool> nsm_faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout);
// Renders the base map's faces that some covered pixel of `g` looks up (its face along p − L).
void build_nsm_base_map(const Scene& scene, const GBuffer& g, int res, LightMap& map);
// The map's nearest texel along p − L for every pixel: the stored radial distance × far in
// metres (far where the texel saw nothing), 0 where the pixel is not covered.
std::vector<float> nsm_map_distances(const Scene& scene, const GBuffer& g, int res,
                                     const LightMap& map);

// The texel index (Receiver::texel) of that nearest texel per pixel, kNoTexel where the pixel is
// not covered or faces away from the light (the detail score's texel image).
ImageU32 nsm_map_texels(const Scene& scene, const GBuffer& g, int res, const LightMap& map);

struct NsmFeatures {
  int width = 0, height = 0;
  float scale = 1.0f;                      // s
  std::vector<std::string> names;          // the planes' names, in order
  std::vector<std::vector<float>> planes;  // width·height each, row-major
  std::vector<uint8_t> coverage;           // 1 where the GBuffer covers the pixel

  const std::vector<float>& plane(const std::string& name) const;
};

// The features `names` (each of nsm_feature_names()) of every GBuffer pixel, with scale s
// (> 0) and size code r_e for c_e_r, reading the base map `map` built for (scene, g, res).
NsmFeatures compute_nsm_features(const Scene& scene, const GBuffer& g, int res,
                                 const LightMap& map, float scale, float size_code,
                                 const std::vector<std::string>& names);

}  // namespace shadowlab
