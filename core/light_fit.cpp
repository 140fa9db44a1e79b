#include "core/light_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace shadowlab {

namespace {

// farthest_corner_distance in double: a light far away (1e20 m) would overflow float's squares.
double farthest_corner(const Bounds& b, const vec3& from) {
  double reach = 0.0;
  for (int i = 0; i < 8 && b.valid(); ++i) {
    const double d[3] = {double((i & 1) ? b.hi.x : b.lo.x) - double(from.x),
                         double((i & 2) ? b.hi.y : b.lo.y) - double(from.y),
                         double((i & 4) ? b.hi.z : b.lo.z) - double(from.z)};
    reach = std::max(reach, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  return reach;
}

}  // namespace

float covering_far(const Scene& scene) {
  const Bounds b = scene_bounds(scene);
  const float reach = farthest_corner_distance(b, scene.light.position);
  // In float where it is finite (farthest_corner_distance's bits, which the built-in framing
  // shares), else in double (a light 1e20 m away overflows float's squares).
  return std::isfinite(1.02f * reach) ? 1.02f * reach
                                      : float(1.02 * farthest_corner(b, scene.light.position));
}

void cover_scene_with_light_range(Scene& scene) {
  scene.light.far = std::max(scene.light.far, covering_far(scene));
  scene.light.near = std::min(scene.light.near, 1e-3f * scene.light.far);
}

double light_depth_step(const PointLight& light) { return double(light.far) * std::ldexp(1.0, -23); }

double scene_span_texels(const Scene& scene, int res) {
  const Bounds b = scene_bounds(scene);
  if (!b.valid()) return 0.0;
  const vec3 c = b.centre();
  const vec3 e = b.extent();
  const double r = 0.5 * std::sqrt(double(e.x) * e.x + double(e.y) * e.y + double(e.z) * e.z);
  const vec3 L = scene.light.position;
  const double dx = double(L.x) - c.x, dy = double(L.y) - c.y, dz = double(L.z) - c.z;
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(d > r)) return std::numeric_limits<double>::infinity();
  return 2.0 * std::asin(r / d) / (0.5 * M_PI) * double(res);
}

LightFitProblem light_fit_problem(const Scene& scene) {
  const Bounds b = scene_bounds(scene);
  if (!b.valid()) return {};
  const PointLight& l = scene.light;
  const double diagonal = double(glm::length(b.extent()));
  const double step = light_depth_step(l);
  if (step > diagonal / kDepthStepsPerScene)
    return {LightFitProblem::Depth, fmt::format(
        "float depth cannot resolve the scene from this light: {:.3g} m away a depth step is "
        "{:.3g} m, more than 1/{:g} of the scene's {:.3g} m diagonal",
        step * std::ldexp(1.0, 23), step, kDepthStepsPerScene, diagonal)};
  if (l.radius > 0.0f) {
    const vec3 e = scene.camera.eye - l.position;
    const double to_eye = std::sqrt(double(e.x) * e.x + double(e.y) * e.y + double(e.z) * e.z);
    if (to_eye <= double(l.radius))
      return {LightFitProblem::Camera, fmt::format("the light's sphere (radius {:g} m) contains the camera ({:.3g} m from its centre)",
                         double(l.radius), to_eye)};
    if (farthest_corner(b, l.position) <= double(l.radius))
      return {LightFitProblem::Scene,
              fmt::format("the light's sphere (radius {:g} m) encloses the whole scene", double(l.radius))};
  }
  return {};
}

}  // namespace shadowlab
