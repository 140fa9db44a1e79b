#include "techniques/pipeline/map_params.h"

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/pipeline/map_filter.h"

namespace shadowlab {

namespace {

MapKey* find_key(std::vector<MapKey>& keys, const char* name) {
  for (MapKey& k : keys)
    if (std::string(k.name) == name) return &k;
  return nullptr;
}

// depth_format_names() as a Choice's "a|b|c".
const char* depth_choices() {
  static const std::string text = [] {
    std::string s;
    for (const std::string& n : depth_format_names()) s += (s.empty() ? "" : "|") + n;
    return s;
  }();
  return text.c_str();
}

// Keys every light-map technique reads, first, in this order.
std::vector<MapKey> shared_keys() {
  return {
      {.name = "res", .type = KeyType::Integer, .def = 512, .lo = 1, .hi = 4096,
       .help = "map resolution: the cube face's edge in texels (tetrahedral: ~6·res² texels in "
               "all; dual-paraboloid: ~3·res² per hemisphere; projector: the face's height)",
       .tune = "256..1024/x2",
       .store = [](MapParams& p, const KeyValue& v) { p.res = int(v.number); }},
      {.name = "bias", .type = KeyType::Number, .def = 0.01, .lo = 0.0, .hi = 1e3,
       .help = "constant depth bias, m, subtracted from the receiver's radial distance",
       .store = [](MapParams& p, const KeyValue& v) { p.bias = float(v.number); }},
      {.name = "slope", .type = KeyType::Number, .def = 1.0, .lo = 0.0, .hi = 1e3,
       .help = "slope-scaled bias: × texel size at the receiver × tan(angle to the light) "
               "(tan <= 10) × the filter's reach",
       .store = [](MapParams& p, const KeyValue& v) { p.slope = float(v.number); }},
      {.name = "normal", .type = KeyType::Number, .def = 0.0, .lo = 0.0, .hi = 1e3,
       .help = "normal offset: the lookup point moves along the geometric normal by normal × "
               "texel size × (1 - N·L)",
       .store = [](MapParams& p, const KeyValue& v) { p.normal = float(v.number); }},
      {.name = "depth", .type = KeyType::Choice, .def_word = "f32", .choices = depth_choices(),
       .help = "stored precision of the distances, quantized before any filtering "
               "(techniques/pipeline/depth_quantize.h)",
       .store = [](MapParams& p, const KeyValue& v) { p.depth = depth_format_from_name(v.word); }},
  };
}

// Split pieces have images of at most tess texels, so a face of E² texels ends with about
// 2·E²/tess² of them (plus the input triangles): bounded before any work (32M pieces, ~1.2 GB
// of vertices per face).
void check_tess(const KeyCheck& c, MapParams& p) {
  const double e = double(paraboloid_face_edge(p.res));
  const double pieces = p.tess > 0 ? 2.0 * e * e / (double(p.tess) * double(p.tess)) : 0.0;
  if (pieces > 3.2e7)
    throw InputError(c.flag, fmt::format("{}: 'tess={}' at res={} would split each face into ~{:.0f}M "
                                         "triangles (limit 32M): raise tess or lower res",
                                         c.name, p.tess, p.res, pieces / 1e6));
}

// Keys a layout adds after the shared ones.
std::vector<MapKey> layout_keys(FaceLayoutKind layout) {
  if (layout != FaceLayoutKind::DualParaboloid) return {};
  return {{.name = "tess", .type = KeyType::Integer, .def = 0, .lo = 0, .hi = 4096,
           .help = "split triangles whose image has an edge longer than tess texels before the "
                   "paraboloid projection (0: off)",
           .store = [](MapParams& p, const KeyValue& v) { p.tess = int(v.number); },
           .check = check_tess}};
}

}  // namespace

MapKey map_blur_key() {
  return {.name = "blur", .type = KeyType::Integer, .def = 3, .lo = 1, .hi = 63,
          .help = "separable box filter width, texels, odd (1: none)",
          .store = [](MapParams& p, const KeyValue& v) { p.blur = int(v.number); },
          .check = [](const KeyCheck& c, MapParams& p) {
            if (p.blur % 2 == 0)
              throw InputError(c.flag, c.name + ": 'blur' must be odd, got " + std::to_string(p.blur));
          }};
}

MapKey map_rpdb_key() {
  return {.name = "rpdb", .type = KeyType::Flag, .def = 0,
          .help = "receiver-plane depth bias: each tap compares with the receiver plane's depth "
                  "at the tap (techniques/lookup/map_receiver.h) instead of the slope term; needs the "
                  "guard band",
          .store = [](MapParams& p, const KeyValue& v) { p.rpdb = v.number != 0.0; },
          .check = [](const KeyCheck& c, MapParams& p) {
            if (!p.rpdb) return;
            if (c.reader.has("slope") && p.slope > 0.0f)
              throw InputError(c.flag, c.name + ": 'rpdb=1' replaces the slope bias; drop 'slope' or set it to 0");
            p.slope = 0.0f;
          }};
}

std::vector<MapKey> map_keys(FaceLayoutKind layout, MapFilter filter) {
  std::vector<MapKey> keys = shared_keys();
  for (MapKey& k : layout_keys(layout)) keys.push_back(std::move(k));
  for (const MapKey& k : map_filter_ops(filter).keys()) keys.push_back(k);
  // The rules of a layout × filter pair, each stated once:
  // the filtering techniques take no bias: the filter absorbs a surface's own depth variation;
  // pcss compares depths like depth compare and keeps the constant bias, but its wide kernels
  // take the receiver-plane depth bias (rpdb=1) instead of the slope term.
  if (filter != MapFilter::Depth) find_key(keys, "slope")->def = 0.0;
  if (filter != MapFilter::Depth && filter != MapFilter::Pcss) find_key(keys, "bias")->def = 0.0;
  if (filter == MapFilter::Depth) {
    MapKey& res = *find_key(keys, "res");
    res.tune = layout == FaceLayoutKind::DualParaboloid ? "512..2048/x2" : "256..2048/x2";
    if (layout == FaceLayoutKind::Tetrahedron) find_key(keys, "pcf")->tune = "1|3";
    if (layout == FaceLayoutKind::DualParaboloid) find_key(keys, "pcf")->tune = "";
  }
  // The cube depth map goes to 8192 (6 × 256 MiB); the other layouts and the filters, whose
  // scratch is double precision, stop at 4096. The cube's depth compare reads taps beyond a face
  // in the neighbouring face by default; the other layouts use guard bands.
  if (layout == FaceLayoutKind::Cube && filter == MapFilter::Depth) {
    find_key(keys, "res")->hi = 8192;
    find_key(keys, "seams")->def_word = "cross";
  }
  return keys;
}

MapParams default_map_params(FaceLayoutKind layout, MapFilter filter) {
  MapParams p;
  p.layout = layout;
  p.filter = filter;
  store_defaults(map_keys(layout, filter), p);
  return p;
}

MapParams parse_map_params(const TechniqueSpec& spec, FaceLayoutKind layout, MapFilter filter,
                           const char* flag) {
  MapParams p;
  p.layout = layout;
  p.filter = filter;
  const std::vector<MapKey> keys = map_keys(layout, filter);
  store_defaults(keys, p);
  SpecReader r(spec, flag);
  read_keys(r, spec.name, flag, keys, p);
  r.reject_unknown();
  return p;
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
