#pragma once
// The built-in "bunny" scene of the slide-projector experiment (Dowling): the Stanford bunny
// of assets/bunny (69,451 triangles, ~0.155 m wide, metres as stored) standing on a
// ground quad in front of a back wall, seen from the front; a posed projector in front of it,
// up and to the left, so the bunny's shadow falls on the wall and the ground.
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

// Index of the bunny mesh in the scene (LOD experiments replace it).
constexpr int kBunnyMesh = 0;

// Builds the scene (InputError naming "--scene bunny" when the asset is missing). Layout, with
// b = the bunny's bounds and c its centre:
//   ground: y = b.lo.y, x in c.x ± 0.4, z from the wall to c.z + 0.5, albedo 0.7
//   wall:   z = b.lo.z − 0.06, facing +z, x in c.x ± 0.4, y up to b.lo.y + 0.4, albedo 0.7
//   camera: c + (0, 0.04, 0.50) looking at c, fov_y 30°, 1024 × 768
//   light:  c + (−0.15, 0.20, 0.40), radius 0.003 m (the point light when no slide is set)
//   projector pose: at the light, aimed at c, fov_y 36°, aspect 1 (the bunny sits inside the
//           spot's flat core, radius 0.6 of the slide's half side)
Scene make_bunny_scene(std::vector<std::string>* notes = nullptr);

}  // namespace shadowlab
