#pragma once
// The JSON scene file (`--scene my.json`): models with transforms, camera, light or slide
// projector, and a ground plane, optionally over a built-in scene. Schema (every key optional
// unless said; lengths in metres, angles in degrees; docs/scenes.md):
//
//   {
//     "base": "default",                  a built-in scene to start from (its meshes, camera
//                                         and light); without it the scene starts empty
//     "models": [                         OBJ or glTF files, paths relative to this file
//       {"file": "bunny.obj",             required
//        "scale": 1.0 | [sx, sy, sz],     applied first
//        "rotate_deg": [rx, ry, rz],      then about x, then y, then z
//        "translate": [x, y, z]}          last
//     ],
//     "camera": {"eye": [..], "target": [..], "up": [0, 1, 0], "fov_deg": 60,
//                "width": 1024, "height": 768, "near": .., "far": ..},
//     "light": {"position": [..], "radius": 0.0, "near": .., "far": ..},
//     "projector": {"position": [..], "target": [..], "up": [0, 1, 0], "fov_deg": 40,
//                   "aspect": 1, "slide": "spot"},     (the light becomes this projector)
//     "ground": {"y": 0, "size": 20}      a square floor quad centred under the bounds (y:
//                                         default the bounds' bottom; size: default 2 × the
//                                         bounds' diagonal)
//   }
//
// A camera or light given only in part keeps the base's (or the framed) values for the rest.
// Without a base, a camera or light the file does not give is framed from the bounds as for
// an OBJ (scenes/scene_library.h frame_from_bounds), with a note. Models bring geometry and
// materials only: a glTF model's own lights and cameras are not used here (give them in the
// file). The light's far distance grows to reach every corner of the scene bounds when the
// file does not set it.
//
// Errors: InputError(path, "<key path>: <reason>") for JSON syntax errors (with the byte
// offset), unknown keys (naming them and the known ones), wrong types, non-finite or
// out-of-range numbers, a missing model file (the model loader's own error names it), and a
// file over 1 MB (a scene file is small; this bounds the parser's memory).
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

Scene load_scene_file(const std::string& path, std::vector<std::string>* notes = nullptr);

// True for a path ending in .json (any case).
bool is_scene_file_path(const std::string& path);

}  // namespace shadowlab
