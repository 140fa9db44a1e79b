#pragma once
// The built-in scenes "default" and "plane" (scenes/scene_registry.h describes them).
#include "core/scene.h"

namespace shadowlab {

Scene make_default_scene();
Scene make_plane_scene();

}  // namespace shadowlab
