#pragma once
// Small helpers shared by the technique tests.
#include "core/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "techniques/technique.h"

namespace shadowlab::test {

// Built-in scene at a reduced image size (tests stay fast on 2 cores).
inline Scene small_scene(const std::string& name, int w, int h) {
  Scene s = make_builtin_scene(name);
  s.camera.width = w;
  s.camera.height = h;
  return s;
}

inline ShadowResult run(const std::string& spec, const Scene& scene, const GBuffer& g) {
  RunOptions opt;
  return run_technique(parse_technique_spec(spec, "--technique"), scene, g, opt);
}

}  // namespace shadowlab::test
