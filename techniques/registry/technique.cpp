#include "techniques/registry/technique.h"

#include <functional>

#include <fmt/format.h>

#include "core/error.h"
#include "core/light_fit.h"
#include "core/parallel.h"
#include "techniques/pipeline/light_map.h"
#include "techniques/pipeline/map_params.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/nsm/nsm_features.h"
#include "techniques/nsm/nsm_technique.h"
#include "techniques/rt/ray_traced.h"
#include "techniques/rt/rt_denoised.h"

namespace shadowlab {
namespace {

// One registry row. `parse` is the validation: it reads every key of a spec (InputError naming
// the flag for an unknown or bad one); `run` parses again and runs.
struct Entry {
  std::string name;
  std::string what;         // what it is
  std::vector<KeyInfo> keys;  // its declared keys, in reading order
  std::function<void(const TechniqueSpec&, const char* flag)> parse;
  std::function<ShadowResult(const TechniqueSpec&, const Scene&, const GBuffer&, const RunOptions&)> run;
  bool needs_projector = false;  // the projector layout: the scene needs --slide
  std::function<uint64_t(const TechniqueSpec&, const Scene&, const char*)> map_bytes;
  // What the technique needs of the scene beyond the projector (throws InputError naming flag).
  std::function<void(const TechniqueSpec&, const Scene&, const char*)> check_scene;
};

// A light map must resolve the scene: at least kMinSceneTexels across it (core/light_fit.h). The
// projector layout is exempt: its one face is aimed and sized by the projector's frustum.
void check_map_spans_scene(const TechniqueSpec& spec, const MapParams& p, const Scene& scene,
                           const char* flag) {
  if (p.layout == FaceLayoutKind::Projector) return;
  const double texels = scene_span_texels(scene, p.res);
  if (texels >= kMinSceneTexels) return;
  throw InputError(flag, fmt::format("{}: the scene spans {:.3g} texels of its map from the light "
                                     "{:.3g} m away (at least {:g} needed: a smaller map records "
                                     "next to nothing); raise res or move the light closer",
                                     spec.text, texels,
                                     double(glm::length(scene.light.position - scene_bounds(scene).centre())),
                                     kMinSceneTexels));
}

struct LayoutName {
  char letter;
  FaceLayoutKind kind;
  const char* what;
};
// The naming rule: a layout letter + a filter's suffix. Every pair of a layout and a filter of map_filters() (techniques/pipeline/map_filter.h) is a technique.
const LayoutName kLayouts[] = {
    {'c', FaceLayoutKind::Cube, "cube (6 faces of 90°)"},
    {'t', FaceLayoutKind::Tetrahedron, "tetrahedral (4 faces in quadrants of one ~6·res² texture)"},
    {'p', FaceLayoutKind::Projector, "projector (one face over the slide projector's frustum; needs --slide)"},
    {'d', FaceLayoutKind::DualParaboloid, "dual-paraboloid (2 hemispheres of ~3·res² texels)"},
};

std::vector<Entry> make_registry() {
  std::vector<Entry> rows;
  rows.push_back({"rt", "Embree ray tracing, the reference", key_infos(ray_traced_keys()),
                  [](const TechniqueSpec& s, const char* flag) { parse_ray_traced(s, flag); },
                  run_ray_traced, false,
                  [](const TechniqueSpec&, const Scene&, const char*) { return uint64_t(0); },
                  [](const TechniqueSpec&, const Scene&, const char*) {}});
  rows.push_back({"rts", "Embree ray tracing at a few samples per pixel, denoised",
                  key_infos(rt_denoised_keys()),
                  [](const TechniqueSpec& s, const char* flag) { parse_rt_denoised(s, flag); },
                  run_rt_denoised, false,
                  [](const TechniqueSpec&, const Scene& scene, const char*) {
                    // The noisy mask, the filter's two images and its guide (7 planes).
                    return uint64_t(scene.camera.width) * uint64_t(scene.camera.height) * 40u;
                  },
                  [](const TechniqueSpec&, const Scene&, const char*) {}});
  rows.push_back({"nsm", "Neural Shadow Mapping: a UNet on one plain cube map's features",
                  key_infos(nsm_keys()),
                  [](const TechniqueSpec& s, const char* flag) { load_nsm_weights(parse_nsm(s, flag), flag); },
                  run_nsm, false,
                  [](const TechniqueSpec& s, const Scene& scene, const char* flag) {
                    return nsm_technique_bytes(s, scene, nullptr, flag);
                  },
                  [](const TechniqueSpec& s, const Scene& scene, const char* flag) {
                    const NsmParams p = parse_nsm(s, flag);
                    check_map_spans_scene(s, nsm_base_map_params(p.res, p.layout), scene, flag);
                  }});
  for (const LayoutName& l : kLayouts)
    for (const MapFilterOps* f : map_filters()) {
      const FaceLayoutKind layout = l.kind;
      const MapFilter filter = f->id;
      rows.push_back(
          {std::string(1, l.letter) + f->suffix,
           std::string(f->what) + " on the " + l.what + " layout",
           key_infos(map_keys(layout, filter)),
           [layout, filter](const TechniqueSpec& s, const char* flag) {
             parse_map_params(s, layout, filter, flag);
           },
           [layout, filter](const TechniqueSpec& s, const Scene& scene, const GBuffer& g,
                            const RunOptions& o) {
             return run_light_map(parse_map_params(s, layout, filter, o.flag), scene, g, o);
           },
           layout == FaceLayoutKind::Projector,
           [layout, filter](const TechniqueSpec& s, const Scene& scene, const char* flag) {
             return light_map_bytes(parse_map_params(s, layout, filter, flag), scene);
           },
           [layout, filter](const TechniqueSpec& s, const Scene& scene, const char* flag) {
             check_map_spans_scene(s, parse_map_params(s, layout, filter, flag), scene, flag);
           }});
    }
  return rows;
}

const std::vector<Entry>& registry() {
  static const std::vector<Entry> rows = make_registry();
  return rows;
}

const Entry& find(const TechniqueSpec& spec, const char* flag) {
  for (const Entry& e : registry())
    if (spec.name == e.name) return e;
  std::string known;
  for (const Entry& e : registry()) known += (known.empty() ? "" : ", ") + e.name;
  throw InputError(flag, "unknown technique '" + spec.name + "' (known: " + known + ")");
}

}  // namespace

ShadowResult run_technique(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                           const RunOptions& options) {
  ShadowResult r = find(spec, options.flag).run(spec, scene, gbuffer, options);
  if (scene.projector.enabled) gate_by_projector(scene, gbuffer, r);
  return r;
}

void gate_by_projector(const Scene& scene, const GBuffer& g, ShadowResult& r) {
  const ProjectorFrame frame = projector_frame(scene.projector);
  parallel_for_chunks(g.pixel_count(), 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      vec2 st;
      if (!g.covered[i] || projector_slide_coords(frame, scene.projector.position, g.position[i], st))
        continue;
      r.mask.data[i] = 0.0f;
      if (!r.texels.empty()) r.texels.data[i] = kNoTexel;
    }
  });
}

void validate_technique(const TechniqueSpec& spec, const char* flag) {
  find(spec, flag).parse(spec, flag);
}

void validate_technique_for_scene(const TechniqueSpec& spec, const Scene& scene, const char* flag) {
  const Entry& e = find(spec, flag);
  e.parse(spec, flag);
  if (e.needs_projector && !scene.projector.enabled)
    throw InputError(flag, spec.name + " needs a slide projector light (--slide)");
  e.check_scene(spec, scene, flag);
}

uint64_t technique_map_bytes(const TechniqueSpec& spec, const Scene& scene, const char* flag) {
  const Entry& e = find(spec, flag);
  // The projector layout needs the projector's aspect; without one validation already failed.
  if (e.needs_projector && !scene.projector.enabled) return 0;
  return e.map_bytes(spec, scene, flag);
}

std::vector<std::pair<std::string, std::string>> technique_list() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Entry& e : registry()) out.emplace_back(e.name, e.what + "; keys: " + keys_text(e.keys));
  return out;
}

std::string technique_list_text() {
  std::string s;
  for (const auto& [name, description] : technique_list()) s += "  " + name + "  " + description + "\n";
  return s;
}

std::vector<KeyInfo> technique_keys(const std::string& name, const char* flag) {
  return find(parse_technique_spec(name, flag), flag).keys;
}

std::string technique_what(const std::string& name, const char* flag) {
  return find(parse_technique_spec(name, flag), flag).what;
}

std::string technique_tune_space(const std::string& name, const char* flag) {
  std::string s = name;
  for (const KeyInfo& k : technique_keys(name, flag))
    if (!k.tune.empty()) s += (s == name ? ":" : ",") + k.name + "=" + k.tune;
  return s;
}

std::vector<char> technique_layout_letters() {
  std::vector<char> out;
  for (const LayoutName& l : kLayouts) out.push_back(l.letter);
  return out;
}

std::vector<std::string> technique_filter_suffixes() {
  std::vector<std::string> out;
  for (const MapFilterOps* f : map_filters()) out.push_back(f->suffix);
  return out;
}

std::string technique_naming_text() {
  std::string layouts, filters;
  for (char c : technique_layout_letters()) layouts += (layouts.empty() ? "" : "/") + std::string(1, c);
  for (const std::string& f : technique_filter_suffixes()) filters += (filters.empty() ? "" : "/") + f;
  return "a layout letter " + layouts + " + a filter " + filters;
}

}  // namespace shadowlab
