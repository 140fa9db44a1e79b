#pragma once
// Merging scenes: the one place that re-bases a scene's material and texture indices (alpha and
// colour textures) when its content is appended to another scene.
#include "core/scene.h"

namespace shadowlab {

// Appends src's meshes, materials and textures to dst, every index re-based; geometry as given
// (callers transform it first). Keeps dst's light, camera and projector.
void append_scene(Scene& dst, Scene src);

}  // namespace shadowlab
