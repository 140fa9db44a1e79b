#pragma once
// Ray-traced twins of rasterized perspective views, to cross-check the rasterizer texel by
// texel: a shadow-map face (or any perspective view) rendered with proj · view has, per texel,
// the closest triangle and the view depth of what the ray from the eye through that texel's
// centre hits first.
#include <limits>

#include "core/math.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"

namespace shadowlab {

// Closest hits of one ray per texel centre (x + 0.5, y + 0.5) of a width × height target
// (origin top-left, y down), for the view `view` (world → view, rigid: rotation + translation;
// the eye looks down −z) and the perspective projection `proj` (OpenGL style, w_clip = −z_view,
// clip z in [−w, w]) that a rasterizer would use as proj · view:
//  - the ray starts at the eye and runs through the texel centre's NDC point; its direction is
//    (x, y, −1) in view space, so the hit distance t IS the view depth along −z (what
//    1 / DepthTarget::inv_w holds);
//  - hits count from the projection's near plane (where z_clip = −w_clip, the rasterizer's only
//    depth clip) up to max_depth (+inf by default: the rasterizer does not clip at the far
//    plane either);
//  - mesh_id / prim_id / depth as in PrimaryHits (kNoPrimitive and +inf where nothing is hit);
//    alpha-tested meshes are tested as by every other ray; no back-face culling.
// Rays are traced per 8 × 8 texel tile as one rtcIntersect1M stream, tiles in parallel; each
// texel's result depends on its own ray only, so the output is identical for any thread count.
// Checks (SL_CHECK) that view is rigid and proj is an invertible perspective projection.
PrimaryHits perspective_rays(const EmbreeScene& rt, const mat4& view, const mat4& proj, int width,
                             int height, float max_depth = std::numeric_limits<float>::infinity());

// A square res × res shadow-map face: perspective_rays(rt, view, proj, res, res, max_depth).
PrimaryHits face_rays(const EmbreeScene& rt, const mat4& view, const mat4& proj, int res,
                      float max_depth = std::numeric_limits<float>::infinity());

}  // namespace shadowlab
