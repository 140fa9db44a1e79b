#pragma once
// The built-in "foliage" scene (Krave's stress case for shadow maps): leaf cards with alpha
// cut-outs casting leaf-shaped shadows. The palm tree (assets/palm_tree) and the four
// plants (assets/plants), stored in centimetres, scaled by 0.01 to metres, on a
// 9 × 7 m ground beside a wall, one hard point light above, framed for 1024 × 768.
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

// Layout (metres; ground y = 0, wall z = -2.2 facing +z, x in [-4.5, 4.5], 4.5 m tall):
//   palm tree at (-0.7, 0, -0.9) (4.1 m tall), shrub at (1.6, 0, -1.2), red shrub at
//   (2.6, 0, 0.9), parviflora at (0.5, 0, 1.0), fern at (-2.6, 0.22, 0.7) (raised so its
//   drooping fronds stay above the ground)
//   light: point (radius 0) at (2.5, 5.5, 4.5), above and in front to the right, so the leaves
//   shadow the ground and the wall behind them; far = 1.02 × the farthest scene corner
//   camera: (0, 2.4, 7.2) looking at (0, 1.5, -0.6), fov_y 50°, 1024 × 768
// Leaves use the palm's map_d and the plants' map_Kd alpha (cutoff 0.5 from the loader).
// InputError naming "--scene foliage" when an asset is missing.
Scene make_foliage_scene(std::vector<std::string>* notes = nullptr);

}  // namespace shadowlab
