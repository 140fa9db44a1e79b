#pragma once
// Parameters of the face-map techniques (the generic layouts of techniques/light_faces.h):
//   tsm          tetrahedral shadow map, depth comparison with PCF
//   psm          projector shadow map: one perspective face, the slide projector's frustum
//                (scene.projector), depth comparison with PCF
//   cvsm, tvsm   variance shadow maps on the cube / tetrahedral layout
//   cesm, tesm   exponential shadow maps on the cube / tetrahedral layout
// Spec keys (all techniques): res (comparable cube edge N; psm: the map's height), bias (m),
// slope, normal, depth (stored precision, techniques/depth_quantize.h); tsm, psm: pcf; moment maps: blur; VSM: min_variance (m²), bleed, maxdepth_eps (m), slope_moment,
// fp32; ESM: c. Units, defaults and meanings are in the struct below.
#include <string>

#include "techniques/depth_quantize.h"
#include "techniques/light_faces.h"
#include "techniques/technique_spec.h"

namespace shadowlab {

enum class MapFilter { Depth, Variance, Exponential };

struct FaceMapParams {
  FaceLayoutKind layout = FaceLayoutKind::Tetrahedron;
  MapFilter filter = MapFilter::Depth;
  int res = 512;          // cube face edge N; the tetrahedral texture has ~6·N² texels;
                          // psm: height N, width round(N × aspect), guard excluded
  DepthFormat depth = DepthFormat::F32;  // stored precision, quantized before any filtering
  // Bias modes, metres, applied to the receiver's radial distance before comparison:
  float bias = 0.01f;     // constant
  float slope = 1.0f;     // × texel size at the receiver × tan(angle to light) (tan <= 10) × filter reach
  float normal = 0.0f;    // normal offset: lookup point moved along the geometric normal by
                          // normal × texel size at the receiver × (1 - N·L)
  int pcf = 1;            // depth: 1 = nearest texel, odd N >= 3 = N×N bilinear-weighted taps
  int blur = 3;           // moment maps: separable box filter width, texels (odd; 1 = none)
  double min_variance = 1e-6;  // VSM: variance floor, m² (1 mm standard deviation)
  double bleed = 0.0;          // VSM: light-bleeding reduction, p -> linstep(bleed, 1, p)
  double maxdepth_eps = 0.0;   // VSM (Krave): > 0 stores the footprint's max depth; a receiver
                               // deeper than max + eps (m) is fully shadowed
  bool slope_moment = false;   // VSM (Krave): M2 = d² + ¼((∂d/∂x)² + (∂d/∂y)²) per texel
  bool moments_fp32 = false;   // VSM: fp32 moments (d, d²) filtered in float — the naive form,
                               // kept to measure its cancellation; default: double filter,
                               // stored as (mean, variance)
  double c = 200.0;            // ESM exponent on normalised distance (|p - L| / far); the
                               // log-space filter allows any c <= 700 (README: why 200)
};

// True for the names this family implements.
bool is_face_map_technique(const std::string& name);
// Parses and range-checks a spec of this family (InputError names `flag` and the key).
FaceMapParams parse_face_map_params(const TechniqueSpec& spec, const char* flag);
// Guard texels each face needs so that every tap and filter stays inside the face's image.
int face_map_guard(const FaceMapParams& p);

}  // namespace shadowlab
