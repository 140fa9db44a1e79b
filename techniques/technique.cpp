#include "techniques/technique.h"

#include "core/error.h"
#include "core/parallel.h"
#include "techniques/cube_shadow_map.h"
#include "techniques/face_map_technique.h"
#include "techniques/ray_traced.h"

namespace shadowlab {
namespace {

using RunFn = ShadowResult (*)(const TechniqueSpec&, const Scene&, const GBuffer&, const RunOptions&);

struct Entry {
  const char* name;
  const char* description;
  RunFn run;
};

// The registry: one line per technique.
const Entry kTechniques[] = {
    {"rt", "Embree ray tracing (reference): rt:spp=256,hard=0,seed=1", run_ray_traced},
    {"csm", "cube shadow map: csm:res=512,pcf=1,bias=0.01,slope=1,normal=0,depth=f32", run_cube_shadow_map},
    {"psm", "projector shadow map (one face, the slide projector's frustum; needs --slide): "
            "psm:res=512,pcf=1,bias=0.01,slope=1,normal=0,depth=f32", run_face_map_technique},
    {"tsm", "tetrahedral shadow map (4 faces in quadrants of one ~6·res² texture): "
            "tsm:res=512,pcf=1,bias=0.01,slope=1,normal=0", run_face_map_technique},
    {"cvsm", "cube variance shadow map: cvsm:res=512,blur=3,min_variance=1e-6,bleed=0,"
             "maxdepth_eps=0,slope_moment=0,fp32=0,bias=0,slope=0,normal=0", run_face_map_technique},
    {"tvsm", "tetrahedral variance shadow map (keys as cvsm)", run_face_map_technique},
    {"cesm", "cube exponential shadow map: cesm:res=512,blur=3,c=200,bias=0,slope=0,normal=0",
     run_face_map_technique},
    {"tesm", "tetrahedral exponential shadow map (keys as cesm)", run_face_map_technique},
};

const Entry& find(const TechniqueSpec& spec, const char* flag) {
  for (const Entry& e : kTechniques)
    if (spec.name == e.name) return e;
  std::string known;
  for (const Entry& e : kTechniques) known += std::string(known.empty() ? "" : ", ") + e.name;
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
  const Entry& e = find(spec, flag);
  if (e.run == run_cube_shadow_map) parse_cube_params(spec, flag);
  if (e.run == run_face_map_technique) parse_face_map_params(spec, flag);
  if (e.run == run_ray_traced) {
    SpecReader r(spec, flag);
    r.get_int("spp", 256, 1, 1 << 20);
    r.get_bool("hard", false);
    r.get_int("seed", 1, 0, 1 << 30);
    r.reject_unknown();
  }
}

std::vector<std::pair<std::string, std::string>> technique_list() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Entry& e : kTechniques) out.emplace_back(e.name, e.description);
  return out;
}


}  // namespace shadowlab
