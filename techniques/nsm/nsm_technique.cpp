#include "techniques/nsm/nsm_technique.h"

#include <chrono>

#include <fmt/format.h>

#include "core/assets.h"
#include "core/error.h"
#include "core/timer.h"
#include "techniques/nsm/nsm_features.h"

namespace shadowlab {

const std::vector<KeyDecl<NsmParams>>& nsm_keys() {
  static const std::vector<KeyDecl<NsmParams>> k = {
      {.name = "weights", .type = KeyType::Text, .def_word = "default",
       .choices = "a .nsmw file; default: the shipped model, assets/nsm/default.nsmw",
       .help = "the network's weights file (tools/nsm/nsm_train.py writes them)",
       .store = [](NsmParams& p, const KeyValue& v) { p.weights = v.word; }},
      {.name = "res", .type = KeyType::Integer, .def = 1024, .lo = 64, .hi = 8192,
       .help = "base map resolution per cube face (the shipped model is trained at 1024)",
       .tune = "512..2048/x2",
       .store = [](NsmParams& p, const KeyValue& v) { p.res = int(v.number); }},
      {.name = "layout", .type = KeyType::Choice, .def_word = "c", .choices = "c|t|d",
       .help = "the base map's layout: cube, tetrahedral or dual-paraboloid (the shipped model is "
               "trained on the cube)",
       .store = [](NsmParams& p, const KeyValue& v) {
         p.layout = v.word == "t" ? FaceLayoutKind::Tetrahedron
                    : v.word == "d" ? FaceLayoutKind::DualParaboloid : FaceLayoutKind::Cube;
       }},
      {.name = "precision", .type = KeyType::Choice, .def_word = "f32", .choices = "f32|f16|bf16",
       .help = "stored activations rounded to 16 bits (arithmetic stays fp32)",
       .store = [](NsmParams& p, const KeyValue& v) {
         p.precision = v.word == "f16" ? NsmPrecision::f16
                       : v.word == "bf16" ? NsmPrecision::bf16 : NsmPrecision::f32;
       }},
  };
  return k;
}

NsmParams parse_nsm(const TechniqueSpec& spec, const char* flag) {
  SpecReader r(spec, flag);
  NsmParams p;
  store_defaults(nsm_keys(), p);
  read_keys(r, spec.name, flag, nsm_keys(), p);
  r.reject_unknown();
  return p;
}

std::string nsm_weights_path(const std::string& weights, const char* flag) {
  return weights == "default" ? asset_path("nsm/default.nsmw", flag) : weights;
}

NsmWeights load_nsm_weights(const NsmParams& p, const char* flag) {
  const std::string path = nsm_weights_path(p.weights, flag);
  NsmWeights w = read_nsm_weights(path);
  for (const std::string& f : w.features)
    if (!is_nsm_feature(f))
      throw InputError(path, "input feature '" + f + "' is not one this build computes");
  return w;
}

namespace {

// Bytes of the tensors nsm_forward stores at width × height: the input, each level's pooled
// output, the skips, the bottleneck and the decoder outputs, and the output (4 B a value).
uint64_t nsm_activation_estimate(const NsmArch& a, int width, int height) {
  auto at = [&](int level) { return uint64_t(width >> level) * uint64_t(height >> level); };
  const int L = a.levels;
  uint64_t values = at(0) * uint64_t(a.features + 1);
  for (int l = 0; l <= L - 2; ++l) values += at(l + 1) * uint64_t(a.widths[size_t(l)]);  // pooled
  for (int l = 1; l <= L - 2; ++l) values += at(l) * uint64_t(a.widths[size_t(l)]);      // skips
  values += at(L - 1) * uint64_t(a.widths[size_t(L - 2)]);                               // mid
  for (int l = 1; l <= L - 2; ++l) values += at(l) * uint64_t(a.widths[size_t(l - 1)]);  // dec
  return 4 * values;
}

}  // namespace

uint64_t nsm_technique_bytes(const TechniqueSpec& spec, const Scene& scene, const GBuffer* g,
                             const char* flag) {
  const NsmParams p = parse_nsm(spec, flag);
  const NsmWeights w = load_nsm_weights(p, flag);
  const int width = g ? g->width : scene.camera.width, height = g ? g->height : scene.camera.height;
  return light_map_bytes(nsm_base_map_params(p.res, p.layout), scene) +
         nsm_activation_estimate(w.arch, width, height);
}

NsmFeatures nsm_spec_features(const TechniqueSpec& spec, const Scene& scene, const GBuffer& g,
                              bool every_candidate, const char* flag) {
  const NsmParams p = parse_nsm(spec, flag);
  const NsmWeights w = load_nsm_weights(p, flag);
  const MapParams mp = nsm_base_map_params(p.res, p.layout);
  LightMap map;
  map.layout = map_layout(mp, scene);
  render_light_map(scene, mp, nsm_faces_needed(scene, g, map.layout), map);
  return compute_nsm_features(scene, g, p.res, map, nsm_scene_scale(scene),
                              nsm_size_code(scene.light.radius),
                              every_candidate ? nsm_feature_names() : w.features);
}

ShadowResult run_nsm(const TechniqueSpec& spec, const Scene& scene, const GBuffer& g,
                     const RunOptions& options) {
  const NsmParams p = parse_nsm(spec, options.flag);
  const NsmWeights w = load_nsm_weights(p, options.flag);
  const NsmNetwork net = nsm_network(w);
  const float scale = nsm_scene_scale(scene), code = nsm_size_code(scene.light.radius);
  const MapParams mp = nsm_base_map_params(p.res, p.layout);
  const size_t n = g.pixel_count();

  ShadowResult r;
  LightMap map;
  map.layout = map_layout(mp, scene);
  r.faces_total = int(map.layout.faces.size());
  std::vector<bool> needed;
  std::vector<float> planes, out(n);
  NsmForwardStats stats;
  std::vector<double> faces_t, render_t, map_t, features_t, network_t, lookup_t;
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    needed = nsm_faces_needed(scene, g, map.layout);
    faces_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    render_light_map(scene, mp, needed, map);
    render_t.push_back(ms_since(t0));
    map_t.push_back(faces_t.back() + render_t.back());
    t0 = std::chrono::steady_clock::now();
    const NsmFeatures f = compute_nsm_features(scene, g, p.res, map, scale, code, w.features);
    planes.resize(f.planes.size() * n);
    for (size_t i = 0; i < f.planes.size(); ++i)
      std::copy(f.planes[i].begin(), f.planes[i].end(), planes.begin() + ptrdiff_t(i * n));
    features_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    nsm_forward(net, planes.data(), g.width, g.height, out.data(), p.precision, &stats);
    network_t.push_back(ms_since(t0));
    lookup_t.push_back(features_t.back() + network_t.back());
  }
  // The mask convention (docs/design.md §4): 1 where no geometry, 0 facing away from the light.
  r.mask = ImageF(g.width, g.height, 1);
  size_t facing = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!g.covered[i]) {
      r.mask.data[i] = 1.0f;
    } else if (!faces_light(g, i, scene.light.position)) {
      r.mask.data[i] = 0.0f;
    } else {
      r.mask.data[i] = out[i];
      ++facing;
    }
  }
  if (options.want_texels) r.texels = nsm_map_texels(scene, g, p.res, map);
  r.faces_ms = median(faces_t);
  r.render_ms = median(render_t);
  r.map_ms = median(map_t);
  r.features_ms = median(features_t);
  r.network_ms = median(network_t);
  r.lookup_ms = median(lookup_t);
  for (bool b : needed) r.faces_needed += b ? 1 : 0;
  r.faces_rendered = r.faces_needed;
  r.triangles_culled = map.dist.triangles_culled;
  WorkCounts& wk = r.work;
  wk.triangles_submitted = map.dist.triangles_submitted;
  wk.triangles_binned = map.dist.triangles_binned;
  wk.texels_rendered = map.dist.texels_rendered;
  wk.pixels_looked_up = facing;
  wk.taps = facing;  // one nearest texel per pixel (the z feature)
  wk.bytes_written = 4 * map.dist.texels_rendered;
  wk.bytes_read = 4 * wk.taps;
  wk.multiply_adds = uint64_t(stats.macs);
  wk.activation_bytes = stats.activation_bytes;
  r.notes = fmt::format("{} levels, {} weights ({}), {:.0f} MAC/px, base map {} {}² on {}/{} faces, "
                        "activations {} {:.1f} MB",
                        w.arch.levels, nsm_parameter_count(w.arch), w.dtype,
                        nsm_macs_per_pixel(w.arch), (p.layout == FaceLayoutKind::Cube ? "cube" : p.layout == FaceLayoutKind::Tetrahedron ? "tetrahedral" : "dual-paraboloid"), p.res, r.faces_rendered, r.faces_total,
                        nsm_precision_name(p.precision), double(stats.activation_bytes) * 1e-6);
  return r;
}

}  // namespace shadowlab
