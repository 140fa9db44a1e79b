#pragma once
// The light against the scene it lights: its range must cover every point of the scene, float
// depth must resolve the scene at that range, and a sphere light must neither hold the camera
// nor swallow the whole scene. One rule for every light, whether a scene file, a built-in scene
// or a flag placed it.
#include <string>

#include "core/scene.h"

namespace shadowlab {

// The far distance that covers the scene from the light: 1.02 × the distance to the farthest
// corner of the scene bounds, so that every stored normalised distance |p - L| / far stays below
// 1 (0 for a scene without vertices).
float covering_far(const Scene& scene);

// The rule of scene files, projectors and lights given by flags: far becomes
// max(far, covering_far) (a far that already covers the scene is kept) and near
// min(near, 1e-3 × far), so that near stays a small fraction of the range.
void cover_scene_with_light_range(Scene& scene);

// The step of float depth at the light's range: float's spacing (2^-23 relative) at far. The
// stored |p - L| / far is rounded at that scale, so two points whose distances from the light
// differ by less are one depth to every shadow map. (|p - L| itself loses p entirely once the
// light is far beyond the scene's coordinates, but then far, which covers the scene, is larger
// still; large coordinates of the scene and light together are the scene's own precision.)
double light_depth_step(const PointLight& light);

// Float depth must resolve the scene: light_depth_step at most kDepthStepsPerScene-th of the
// scene bounds' diagonal (a light 1e20 m away rounds every point of a 10 m room to one distance).
inline constexpr double kDepthStepsPerScene = 1000.0;

// How many texels of a light map of comparable cube edge `res` (a 90° face of res texels, the
// unit every layout's res is given in) the scene's bounding sphere spans from the light: its
// angular diameter 2·asin(r / d) over the texel angle (π/2) / res. Infinite when the light lies
// inside the sphere (the scene then surrounds it on the map).
double scene_span_texels(const Scene& scene, int res);
// A light map must give the scene at least this many texels across: below it, walls and models
// are smaller than a texel, the map records next to nothing and nearly every receiver comes out
// lit (a room 1000 m away spans 2 texels of a 256 map). A floor against maps that cannot resolve
// the scene at all, not a promise of quality: grazing light still aliases above it.
inline constexpr double kMinSceneTexels = 32.0;

// Why a light does not fit its scene (kind None: it fits; `reason` is then empty).
struct LightFitProblem {
  enum Kind {
    None,
    Depth,   // float depth cannot resolve the scene at the light's range (light_depth_step
             // above the bounds' diagonal / kDepthStepsPerScene)
    Camera,  // the light's sphere (radius > 0) contains the camera's eye
    Scene,   // the light's sphere encloses the whole scene bounds (every corner within it)
  };
  Kind kind = None;
  std::string reason;  // one clause, no trailing period
};
// The first problem of the light, in the order above. The far reaching the scene is not checked
// here: a file may give a shorter range on purpose (a glTF light's "range");
// cover_scene_with_light_range grows it where the program chose the light's position.
LightFitProblem light_fit_problem(const Scene& scene);

}  // namespace shadowlab
