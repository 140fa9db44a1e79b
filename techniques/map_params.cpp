#include "techniques/map_params.h"

#include <cstdio>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/map_filter.h"

namespace shadowlab {

MapParams default_map_params(FaceLayoutKind layout, MapFilter filter) {
  MapParams p;
  p.layout = layout;
  p.filter = filter;
  // PCSS compares depths like depth compare and keeps its constant bias; its wide kernels take
  // the receiver-plane depth bias by default instead of the slope term (README "PCSS").
  if (filter != MapFilter::Depth && filter != MapFilter::Pcss) p.bias = p.slope = 0.0f;
  if (filter == MapFilter::Pcss) {
    p.rpdb = true;
    p.slope = 0.0f;
  }
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
  if (layout == FaceLayoutKind::DualParaboloid) {
    p.tess = r.get_int("tess", p.tess, 0, 4096);
    // Split pieces have images of at most tess texels, so a face of E² texels ends with about
    // 2·E²/tess² of them (plus the input triangles): bound that before any work (32M pieces,
    // ~1.2 GB of vertices per face).
    const double e = double(paraboloid_face_edge(p.res));
    const double pieces = p.tess > 0 ? 2.0 * e * e / (double(p.tess) * double(p.tess)) : 0.0;
    if (pieces > 3.2e7)
      throw InputError(flag, fmt::format("{}: 'tess={}' at res={} would split each face into ~{:.0f}M "
                                         "triangles (limit 32M): raise tess or lower res",
                                         n, p.tess, p.res, pieces / 1e6));
  }
  // The filter's own keys (techniques/map_filter.h).
  map_filter_ops(filter).parse_keys(r, n, flag, p);
  r.reject_unknown();
  return p;
}

std::string map_keys_text(FaceLayoutKind layout, MapFilter filter) {
  const MapParams p = default_map_params(layout, filter);
  return fmt::format("res={},bias={:g},slope={:g},normal={:g},depth=f32,{}", p.res,
                     double(p.bias), double(p.slope), double(p.normal),
                     layout == FaceLayoutKind::DualParaboloid ? "tess=0," : "") +
         map_filter_ops(filter).keys_text(p);
}

void read_blur(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.blur = r.get_int("blur", p.blur, 1, 63);
  if (p.blur % 2 == 0)
    throw InputError(flag, name + ": 'blur' must be odd, got " + std::to_string(p.blur));
}

void read_rpdb(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.rpdb = r.get_bool("rpdb", p.rpdb);
  if (!p.rpdb) return;
  if (r.has("slope") && p.slope > 0.0f)
    throw InputError(flag, name + ": 'rpdb=1' replaces the slope bias; drop 'slope' or set it to 0");
  p.slope = 0.0f;
}

int map_guard(const MapParams& p) {
  // PCF reaches (pcf + 1)/2 texels from the lookup centre; a moment map's bilinear lookup
  // reaches 1 texel, whose filtered value reads blur/2 texels further. One more texel covers
  // the rounding of coordinates at a face's edge.
  if (p.filter == MapFilter::Depth) return p.seams == SeamMode::Cross ? 0 : (p.pcf + 1) / 2 + 1;
  // PCSS reads taps beyond a face's image through their direction (any kernel width): the
  // guard only keeps the bilinear footprint of a tap at the edge in its own face.
  if (p.filter == MapFilter::Pcss) return 2;
  return 1 + p.blur / 2 + 1;
}

float map_reach(const MapParams& p) {
  return p.filter == MapFilter::Depth ? 0.5f * float(p.pcf + 1) : 1.0f;
}

}  // namespace shadowlab
