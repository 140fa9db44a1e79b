#pragma once
// The built-in scenes "room100k" and "room1m" (scenes/scene_registry.h describes them).
#include "core/scene.h"

namespace shadowlab {

Scene make_room100k_scene();
Scene make_room1m_scene();

}  // namespace shadowlab
