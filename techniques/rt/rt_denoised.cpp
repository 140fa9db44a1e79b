#include "techniques/rt/rt_denoised.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "core/rng.h"
#include "core/timer.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"

namespace shadowlab {

const std::vector<KeyDecl<RtDenoisedParams>>& rt_denoised_keys() {
  static const std::vector<KeyDecl<RtDenoisedParams>> k = {
      {.name = "spp", .type = KeyType::Integer, .def = 4, .lo = 1, .hi = 1024,
       .help = "shadow rays per pixel on the sphere light (stratified per pixel, as the reference's)",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.spp = int(v.number); }},
      {.name = "denoise", .type = KeyType::Choice, .def_word = "none", .choices = "none|atrous",
       .help = "none: the raw estimate; atrous: edge-avoiding a-trous guided by depth, normal and the values' variance",
       .store = [](RtDenoisedParams& p, const KeyValue& v) {
         p.denoise = v.word == "none" ? Denoiser::none : Denoiser::atrous;
       }},
      {.name = "iterations", .type = KeyType::Integer, .def = 4, .lo = 1, .hi = 8,
       .help = "a-trous iterations: taps up to 2^iterations pixels away", .needs = "denoise=atrous",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.atrous.iterations = int(v.number); }},
      {.name = "sigma_z", .type = KeyType::Number, .def = 1.0, .lo = 0.01, .hi = 100.0,
       .help = "depth edge-stopping scale, in depth gradients per pixel of offset",
       .needs = "denoise=atrous",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.atrous.sigma_z = float(v.number); }},
      {.name = "sigma_v", .type = KeyType::Number, .def = 1.0, .lo = 0.0, .hi = 100.0,
       .help = "value edge-stopping scale in standard deviations of the values' noise (0: none)",
       .needs = "denoise=atrous",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.atrous.sigma_v = float(v.number); }},
      {.name = "normal_power", .type = KeyType::Integer, .def = 7, .lo = 0, .hi = 10,
       .help = "normal edge-stopping: (n_p . n_q)^(2^normal_power)", .needs = "denoise=atrous",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.atrous.normal_power = int(v.number); }},
      {.name = "hard", .type = KeyType::Flag, .def = 0,
       .help = "1: treat the light as a point (one ray per pixel) whatever its radius",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.hard = v.number != 0.0; }},
      {.name = "seed", .type = KeyType::Integer, .def = 1, .lo = 0, .hi = 1 << 30,
       .help = "sample-sequence seed (mixed with the scene seed)",
       .store = [](RtDenoisedParams& p, const KeyValue& v) { p.seed = int(v.number); }},
  };
  return k;
}

RtDenoisedParams parse_rt_denoised(const TechniqueSpec& spec, const char* flag) {
  SpecReader r(spec, flag);
  RtDenoisedParams p;
  store_defaults(rt_denoised_keys(), p);
  read_keys(r, spec.name, flag, rt_denoised_keys(), p);
  r.reject_unknown();
  return p;
}

double mrays_per_second(uint64_t rays, double ms) {
  return ms > 0.0 ? double(rays) / (ms * 1e3) : 0.0;
}

ShadowResult run_rt_denoised(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                             const RunOptions& options) {
  const RtDenoisedParams p = parse_rt_denoised(spec, options.flag);
  const bool hard = p.hard || scene.light.radius <= 0.0f;
  const uint64_t seed = mix64(scene.seed) ^ uint64_t(p.seed);
  ShadowResult res;
  auto t0 = std::chrono::steady_clock::now();
  EmbreeScene rt(scene);
  const double build_ms = ms_since(t0);
  const AtrousGuide guide =
      p.denoise == Denoiser::atrous ? atrous_guide(gbuffer, scene.light.position) : AtrousGuide{};
  const AtrousKernels& kernels = atrous_kernels(process_isa());
  AtrousParams ap = p.atrous;
  ap.samples = hard ? 1 : p.spp;
  std::vector<double> rays_t, denoise_t, lookup_t;
  uint64_t rays = 0, taps = 0;
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    t0 = std::chrono::steady_clock::now();
    ImageF noisy = hard ? hard_visibility(rt, scene, gbuffer, &rays)
                        : soft_visibility(rt, scene, gbuffer, p.spp, seed, nullptr, &rays);
    rays_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    res.mask = p.denoise == Denoiser::atrous ? atrous_denoise(noisy, guide, ap, kernels, &taps)
                                             : std::move(noisy);
    denoise_t.push_back(ms_since(t0));
    lookup_t.push_back(rays_t.back() + denoise_t.back());
  }
  res.rays_ms = median(rays_t);
  res.denoise_ms = median(denoise_t);
  res.lookup_ms = median(lookup_t);
  res.work.pixels_looked_up = 0;
  for (size_t i = 0; i < gbuffer.pixel_count(); ++i)
    res.work.pixels_looked_up +=
        gbuffer.covered[i] &&
        glm::dot(gbuffer.geo_normal[i], scene.light.position - gbuffer.position[i]) > 0.0f;
  res.work.rays = rays;
  res.work.filter_taps = taps;
  res.notes = fmt::format("{} rays per pixel{}, {}; {:.1f} M rays/s; BVH built in {:.2f} ms (once "
                          "per scene, not in the shadow time)",
                          hard ? 1 : p.spp, hard ? " (hard)" : "",
                          p.denoise == Denoiser::atrous
                              ? fmt::format("a-trous x{} ({} taps)", p.atrous.iterations, taps)
                              : std::string("not denoised"),
                          mrays_per_second(rays, res.rays_ms), build_ms);
  return res;
}

}  // namespace shadowlab
