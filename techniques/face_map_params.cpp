#include "techniques/face_map_params.h"

#include "core/error.h"

namespace shadowlab {

bool is_face_map_technique(const std::string& name) {
  return name == "tsm" || name == "psm" || name == "cvsm" || name == "tvsm" || name == "cesm" || name == "tesm";
}

FaceMapParams parse_face_map_params(const TechniqueSpec& spec, const char* flag) {
  FaceMapParams p;
  const std::string& n = spec.name;
  SL_CHECK(is_face_map_technique(n));
  p.layout = n[0] == 't' ? FaceLayoutKind::Tetrahedron
                         : (n[0] == 'p' ? FaceLayoutKind::Projector : FaceLayoutKind::Cube);
  p.filter = n == "tsm" || n == "psm" ? MapFilter::Depth
                        : (n.find("vsm") != std::string::npos ? MapFilter::Variance
                                                              : MapFilter::Exponential);
  SpecReader r(spec, flag);
  p.res = r.get_int("res", p.res, 1, 4096);
  // Filtering techniques need no depth bias by default: the filter itself absorbs the
  // surface's own depth variation (VSM's variance, ESM's soft exponential falloff).
  const bool depth = p.filter == MapFilter::Depth;
  p.bias = float(r.get_double("bias", depth ? p.bias : 0.0, 0.0, 1e3));
  p.slope = float(r.get_double("slope", depth ? p.slope : 0.0, 0.0, 1e3));
  p.normal = float(r.get_double("normal", p.normal, 0.0, 1e3));
  p.depth = depth_format_from_name(r.get_choice("depth", "f32", depth_format_names()));
  if (depth) {
    p.pcf = r.get_int("pcf", p.pcf, 1, 15);
    if (p.pcf > 1 && p.pcf % 2 == 0)
      throw InputError(flag, n + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
  } else {
    p.blur = r.get_int("blur", p.blur, 1, 63);
    if (p.blur % 2 == 0)
      throw InputError(flag, n + ": 'blur' must be odd, got " + std::to_string(p.blur));
  }
  if (p.filter == MapFilter::Variance) {
    p.min_variance = r.get_double("min_variance", p.min_variance, 0.0, 1e6);
    p.bleed = r.get_double("bleed", p.bleed, 0.0, 0.99);
    p.maxdepth_eps = r.get_double("maxdepth_eps", p.maxdepth_eps, 0.0, 1e3);
    p.slope_moment = r.get_bool("slope_moment", p.slope_moment);
    p.moments_fp32 = r.get_bool("fp32", p.moments_fp32);
  }
  if (p.filter == MapFilter::Exponential)
    // exp(c·Δ) with Δ <= 1 must stay below DBL_MAX (ln ≈ 709.8) in the filter; see moment_filter.h.
    p.c = r.get_double("c", p.c, 0.01, 700.0);
  r.reject_unknown();
  return p;
}

int face_map_guard(const FaceMapParams& p) {
  // PCF reaches (pcf + 1)/2 texels from the lookup centre; a moment map's bilinear lookup
  // reaches 1 texel, whose filtered value reads blur/2 texels further. One more texel covers
  // the rounding of coordinates at a face's edge.
  if (p.filter == MapFilter::Depth) return (p.pcf + 1) / 2 + 1;
  return 1 + p.blur / 2 + 1;
}

}  // namespace shadowlab
