#include "techniques/map_params.h"

#include <cstdio>

#include "core/error.h"

namespace shadowlab {

MapParams default_map_params(FaceLayoutKind layout, MapFilter filter) {
  MapParams p;
  p.layout = layout;
  p.filter = filter;
  if (filter != MapFilter::Depth) p.bias = p.slope = 0.0f;
  // csm always looked taps beyond a face up in the neighbouring face; the other layouts were
  // built with guard bands. Both stay the default of their layout (README: seams).
  p.seams = filter == MapFilter::Depth && layout == FaceLayoutKind::Cube ? SeamMode::Cross
                                                                          : SeamMode::Guard;
  return p;
}

MapParams parse_map_params(const TechniqueSpec& spec, FaceLayoutKind layout, MapFilter filter,
                           const char* flag) {
  MapParams p = default_map_params(layout, filter);
  const std::string& n = spec.name;
  SpecReader r(spec, flag);
  // The cube depth map always went to 8192 (6 × 256 MiB); the other layouts and the filters,
  // whose scratch is double precision, stop at 4096.
  const bool cube_depth = layout == FaceLayoutKind::Cube && filter == MapFilter::Depth;
  p.res = r.get_int("res", p.res, 1, cube_depth ? 8192 : 4096);
  p.bias = float(r.get_double("bias", p.bias, 0.0, 1e3));
  p.slope = float(r.get_double("slope", p.slope, 0.0, 1e3));
  p.normal = float(r.get_double("normal", p.normal, 0.0, 1e3));
  p.depth = depth_format_from_name(r.get_choice("depth", "f32", depth_format_names()));
  if (filter == MapFilter::Depth) {
    p.pcf = r.get_int("pcf", p.pcf, 1, 15);
    if (p.pcf > 1 && p.pcf % 2 == 0)
      throw InputError(flag, n + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
    const std::string seams =
        r.get_choice("seams", p.seams == SeamMode::Cross ? "cross" : "guard", {"guard", "cross"});
    p.seams = seams == "cross" ? SeamMode::Cross : SeamMode::Guard;
  } else {
    p.blur = r.get_int("blur", p.blur, 1, 63);
    if (p.blur % 2 == 0)
      throw InputError(flag, n + ": 'blur' must be odd, got " + std::to_string(p.blur));
  }
  if (filter == MapFilter::Variance) {
    p.min_variance = r.get_double("min_variance", p.min_variance, 0.0, 1e6);
    p.bleed = r.get_double("bleed", p.bleed, 0.0, 0.99);
    p.maxdepth_eps = r.get_double("maxdepth_eps", p.maxdepth_eps, 0.0, 1e3);
    p.slope_moment = r.get_bool("slope_moment", p.slope_moment);
    p.moments_fp32 = r.get_bool("fp32", p.moments_fp32);
  }
  if (filter == MapFilter::Exponential)
    // exp(c·Δ) with Δ <= 1 must stay below DBL_MAX (ln ≈ 709.8) in the filter; see moment_filter.h.
    p.c = r.get_double("c", p.c, 0.01, 700.0);
  r.reject_unknown();
  return p;
}

std::string map_keys_text(FaceLayoutKind layout, MapFilter filter) {
  const MapParams p = default_map_params(layout, filter);
  char b[256];
  std::snprintf(b, sizeof b, "res=%d,bias=%g,slope=%g,normal=%g,depth=f32", p.res, double(p.bias),
                double(p.slope), double(p.normal));
  std::string s = b;
  if (filter == MapFilter::Depth)
    s += std::string(",pcf=1,seams=") + (p.seams == SeamMode::Cross ? "cross" : "guard");
  else
    s += ",blur=" + std::to_string(p.blur);
  if (filter == MapFilter::Variance) {
    std::snprintf(b, sizeof b, ",min_variance=%g,bleed=%g,maxdepth_eps=%g,slope_moment=0,fp32=0",
                  p.min_variance, p.bleed, p.maxdepth_eps);
    s += b;
  }
  if (filter == MapFilter::Exponential) {
    std::snprintf(b, sizeof b, ",c=%g", p.c);
    s += b;
  }
  return s;
}

int map_guard(const MapParams& p) {
  // PCF reaches (pcf + 1)/2 texels from the lookup centre; a moment map's bilinear lookup
  // reaches 1 texel, whose filtered value reads blur/2 texels further. One more texel covers
  // the rounding of coordinates at a face's edge.
  if (p.filter == MapFilter::Depth) return p.seams == SeamMode::Cross ? 0 : (p.pcf + 1) / 2 + 1;
  return 1 + p.blur / 2 + 1;
}

float map_reach(const MapParams& p) {
  return p.filter == MapFilter::Depth ? 0.5f * float(p.pcf + 1) : 1.0f;
}

}  // namespace shadowlab
