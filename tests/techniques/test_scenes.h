#pragma once
// Small helpers shared by the technique tests.
#include "scenes/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "techniques/registry/technique.h"

namespace shadowlab::test {

// Built-in scene at a reduced image size (tests stay fast on 2 cores).
inline Scene small_scene(const std::string& name, int w, int h) {
  Scene s = make_builtin_scene(name);
  s.camera.width = w;
  s.camera.height = h;
  return s;
}

// Share of pixels on which two masks fall on different sides of 0.5.
inline double mismatch_rate(const ImageF& a, const ImageF& b) {
  size_t diff = 0;
  for (size_t i = 0; i < a.data.size(); ++i) diff += (a.data[i] > 0.5f) != (b.data[i] > 0.5f);
  return double(diff) / double(a.data.size());
}

inline ShadowResult run(const std::string& spec, const Scene& scene, const GBuffer& g) {
  RunOptions opt;
  return run_technique(parse_technique_spec(spec, "--technique"), scene, g, opt);
}

}  // namespace shadowlab::test
