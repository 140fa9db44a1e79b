#pragma once
// OBJ scene framing and scene edits (ground, projector, image size); the built-in scenes are in
// scenes/scene_registry.h (included here). Units: metres; world right-handed, y up.
#include <string>
#include <vector>

#include "core/scene.h"
#include "scenes/scene_registry.h"

namespace shadowlab {

// Loads an OBJ (see scenes/obj_loader.h) and gives it a camera and a light:
// - If the OBJ's leading comments carry a light and/or camera (read_obj_view_header, e.g.
//   assets/bench/room100k.obj), those are used exactly.
// - Otherwise, with c = bounds centre and r = bounding-sphere radius (half the bounds
//   diagonal): camera at c + d·normalize(0, 1, 1) looking at c, up +y, fov_y 60°, 1024×768,
//   d = 1.05·r / sin(30°) (the sphere fits the vertical fov, and the wider horizontal one),
//   near = max(0.5·(d − r), 1e-3·d), far = 1.5·(d + r);
//   light at c + 1.5·r·normalize(1, 1.5, 0.5) (above, to the +x side), radius 0.01·r,
//   far = 1.02·2.5·r (covers the whole bounding sphere), near = 1e-3·far.
// Notes from the loader go to *notes (else stderr).
Scene make_obj_scene(const std::string& obj_path, std::vector<std::string>* notes = nullptr);

// The framing make_obj_scene gives a model without a camera (camera = true) and/or a light
// (light = true), from the scene bounds; the others are kept. Throws InputError(where, ...) when
// the bounds are too large to frame, or when every triangle has zero area (either way).
void frame_from_bounds(Scene& s, bool camera, bool light, const std::string& where);

// Sets the camera's image size; throws InputError("--size", ...) outside [1, kMaxImageSide].
void apply_camera_size(Scene& scene, int width, int height);

// Appends a square ground quad (8 × 8 grid, front +y, material "ground", albedo 0.7) at the
// bottom of the scene bounds, centred under the bounds centre, of side `size_factor` × the
// bounds diagonal. For OBJ models without a receiver (bunny, plants); make_obj_scene does not
// add it by itself. The light's far is enlarged to reach the quad's corners.
void add_ground_plane(Scene& scene, float size_factor = 2.0f);

// Makes the scene's light the given projector (enabled): the point light moves to the
// projector's position with radius 0, its far grows to 1.02 × the distance to the farthest
// corner of the scene bounds (stored distances stay in [0, 1]) and its near becomes
// min(near, 1e-3 × far). Validates the projector (InputError naming `where`).
void set_projector(Scene& scene, Projector projector, const std::string& where);

}  // namespace shadowlab
