#pragma once
// The shaded image a person looks at, for any scene and any visibility mask (docs/programs/render.md):
//   point light:     colour = albedo × (ambient + max(0, N·L) × visibility)
//   slide projector: shade_projector (techniques/shading/projector_shading.h), the slide's colour in L
// per covered pixel, linear RGB, the light of unit intensity without distance falloff (the
// picture shows where the shadows are, not a radiometric quantity); N is the GBuffer's shading
// normal, L the unit direction to the light, albedo the material's colour texture at the
// pixel's uv times its factor (Material::color_texture: OBJ map_Kd × Kd, glTF baseColorTexture
// × baseColorFactor), else its albedo. Pixels without geometry black.
#include "core/gbuffer.h"
#include "core/image.h"
#include "core/scene.h"

namespace shadowlab {

// 3-channel linear RGB of the GBuffer's size; `visibility` is a mask of that size; ambient in
// [0, 1].
ImageF shade_scene(const Scene& scene, const GBuffer& g, const ImageF& visibility, float ambient);

}  // namespace shadowlab
