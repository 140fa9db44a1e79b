#pragma once
// Built-in scenes and OBJ scene framing. Units: metres; world right-handed, y up.
#include <string>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

// Names accepted by make_builtin_scene, in the order printed by error messages.
std::vector<std::string> builtin_scene_names();

// A built-in scene by name:
//   "default": a Kluczek-style closed 10 × 4 × 10 m room with a box, a sphere, a thin pole, a
//              table on four thin legs and a slanted ramp (grazing receiver) around one small
//              sphere light (radius 0.03 m) at (0.9, 2.7, -0.4); every cube face of the light
//              sees geometry; shadows range from contact to room-long. See the .cpp for every
//              placement.
//   "plane":   one 10 × 10 m floor quad (y = 0, centred on the origin), light 2 m above its
//              centre, camera looking straight down; nothing occludes (analytic tests).
//   "room100k": the benchmark room of ../shared/assets/bench/room100k.obj built in (no asset
//              needed): a 60 × 60 m ground, a 20 × 8 × 20 m room, 32 spheres and 32 tori, one
//              mesh per OBJ group in OBJ order, the OBJ's light (0, 4, 0) and camera; 99,852
//              triangles, the OBJ's tessellation (spheres 40 × 20, tori 40 × 20).
//   "room1m":   the same layout tessellated finer (spheres 128 × 61 = 15,360 triangles, tori
//              128 × 62 = 15,872): 999,436 triangles. See the .cpp for the layout.
//   "bunny":   the Stanford bunny from the shared assets on a ground quad before a wall, with a
//              posed slide projector (core/bunny_scene.h); needs the assets folder.
//   "foliage": the palm tree and four plants (alpha-cut leaf cards) on a ground beside a wall,
//              one hard point light above (core/foliage_scene.h); needs the assets folder.
// Throws InputError("--scene", "unknown built-in scene 'x' (known: default, plane, ...)").
Scene make_builtin_scene(const std::string& name);

// Loads an OBJ (see core/obj_loader.h) and gives it a camera and a light:
// - If the OBJ's leading comments carry a light and/or camera (read_obj_view_header, e.g.
//   bench/room100k.obj), those are used exactly.
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
