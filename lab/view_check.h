#pragma once
// A camera that sees nothing is bad input, not a result: every technique and the reference
// agree on an empty image (mask 1 everywhere), so a blank view would score a perfect 1.000 and
// write blank pictures. Two checks, both before the expensive steps:
//  - scene_from_options (lab/cli.h) refuses a view whose frustum misses the scene's
//    bounds (check_view_sees_bounds), before any pass;
//  - each program refuses a camera pass that covered no pixel (require_covered_view), right
//    after that pass and before any shadow map or reference: geometry inside the frustum can
//    still fall between pixel centres (a scene a million metres away) or lie in the bounds'
//    empty corners.
// A partially empty view (some pixels see no geometry, e.g. sky behind a model) is legitimate:
// those pixels hold mask 1 in every technique and in the reference and agree by construction.
#include <string>

#include "core/gbuffer.h"
#include "core/scene.h"

namespace shadowlab {

// True when the scene bounds lie wholly outside the camera's view frustum (behind the near
// plane, beyond the far plane, or beyond one side), so that no pixel can see the scene. Computed
// in double with a small slack, so a box on a frustum plane counts as seen.
bool bounds_outside_view(const Camera& camera, const Bounds& bounds);

// The flag or file blamed when the scene's view is empty: set by scene_from_options from the
// view flags given (--eye, --target, --fov), else the scene ("--scene plane" or its file).
void set_view_blame(const std::string& scene_name, const std::string& blame);

// InputError(blame, ...) when bounds_outside_view.
void check_view_sees_bounds(const Scene& scene, const std::string& blame);

// InputError(the scene's blame, ...) when the camera pass `g` of `scene` covered no pixel.
void require_covered_view(const Scene& scene, const GBuffer& g);

}  // namespace shadowlab
