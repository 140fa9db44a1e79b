#pragma once
// The slide projector's shaded image (Dowling §4: an ambient pass plus the projector pass):
//   colour = ambient × albedo + slide(p) × albedo × max(0, N·L) × visibility
// per covered pixel, linear RGB; N is the GBuffer's shading normal, L the unit direction from
// the surface point to the projector, slide(p) the projector's slide at p (0 outside its
// frustum, core/projector.h) and visibility the technique's mask (any technique, or the
// reference). Pixels without geometry are black. The mask/metric machinery works on the
// visibility term alone; this image is what a person looks at (and what the LOD masking
// experiment compares).
#include "core/gbuffer.h"
#include "core/image.h"
#include "core/scene.h"

namespace shadowlab {

struct ProjectorShading {
  float ambient = 0.1f;  // ambient light level (fraction of albedo), [0, 1]
};

// 3-channel linear RGB image of the gbuffer's size; needs scene.projector.enabled and a mask of
// the gbuffer's size.
ImageF shade_projector(const Scene& scene, const GBuffer& gbuffer, const ImageF& visibility,
                       const ProjectorShading& shading = {});

// Rec. 709 luminance of a linear RGB image (one channel), for SSIM/RMSE on shaded images.
ImageF luminance(const ImageF& rgb);

}  // namespace shadowlab
