// The built-in scenes "default" (a Kluczek-style room) and "plane" (one floor quad).
#include "scenes/default_scene.h"

#include <cmath>

#include "scenes/mesh_builders.h"

namespace shadowlab {
// The default scene. Room: x, z in [-5, 5], y in [0, 4] (floor y = 0). Light L = (0.9, 2.7,
// -0.4). The cube face an object falls in is the major axis of (object − L).
Scene make_default_scene() {
  Scene s;
  s.name = "default";
  // Room surfaces face inward; 8 × 8 grids (1.25 m cells) on the 10 × 10 m planes, 8 × 4 on
  // the walls (1.25 × 1 m cells), so no triangle is huge.
  add_grid_quad(new_mesh(s, "floor", vec3(0.70f, 0.70f, 0.68f)), vec3(-5, 0, -5), vec3(0, 0, 10),
                vec3(10, 0, 0), 8, 8);  // front +y
  add_grid_quad(new_mesh(s, "ceiling", vec3(0.80f)), vec3(-5, 4, -5), vec3(10, 0, 0),
                vec3(0, 0, 10), 8, 8);  // front -y
  add_grid_quad(new_mesh(s, "wall_north", vec3(0.65f, 0.62f, 0.55f)), vec3(-5, 0, -5),
                vec3(10, 0, 0), vec3(0, 4, 0), 8, 4);  // z = -5, front +z
  add_grid_quad(new_mesh(s, "wall_south", vec3(0.60f, 0.60f, 0.65f)), vec3(-5, 0, 5), vec3(0, 4, 0),
                vec3(10, 0, 0), 4, 8);  // z = +5, front -z
  add_grid_quad(new_mesh(s, "wall_west", vec3(0.70f, 0.55f, 0.50f)), vec3(-5, 0, -5), vec3(0, 4, 0),
                vec3(0, 0, 10), 4, 8);  // x = -5, front +x
  add_grid_quad(new_mesh(s, "wall_east", vec3(0.50f, 0.60f, 0.70f)), vec3(5, 0, -5), vec3(0, 0, 10),
                vec3(0, 4, 0), 8, 4);  // x = +5, front -x

  // Box: 0.9 m cube on the floor at (-1.8, 0.45, -1.2), turned 30° about y. Contact shadow,
  // cast towards -x onto the floor (light face -x).
  add_box(new_mesh(s, "box", vec3(0.75f, 0.45f, 0.30f)),
          box_transform(vec3(-1.8f, 0.45f, -1.2f), vec3(0.9f), 30.0f));

  // Sphere: radius 0.5 m resting on the floor at (1.9, 0.5, 0.9), 32 × 16 (960 triangles),
  // smooth. Contact shadow cast towards +x/+z, the camera (light face -y).
  add_uv_sphere(new_mesh(s, "sphere", vec3(0.30f, 0.55f, 0.75f)), vec3(1.9f, 0.5f, 0.9f), 0.5f, 32,
                16);

  // Pole: radius 0.035 m, 3.2 m tall (above the light's height) at (-0.8, 0, 0.5), 16
  // segments. Thin and long: its shadow crosses the floor and the ramp towards the west wall
  // (light face -x).
  add_cylinder(new_mesh(s, "pole", vec3(0.85f, 0.85f, 0.80f)), vec3(-0.8f, 0.0f, 0.5f), 0.035f,
               3.2f, 16);

  // Table at (2.2, 0, -2.3): top 1.6 (x) × 0.06 × 1.0 (z) m, top surface at 0.78 m; four legs
  // 0.05 × 0.72 × 0.05 m inset 0.08 m from the top's corners. It straddles the -y/-z cube
  // face boundary as seen from the light (a seam case).
  {
    Mesh& table = new_mesh(s, "table", vec3(0.55f, 0.40f, 0.25f));
    const vec3 c(2.2f, 0.0f, -2.3f);
    add_box(table, box_transform(c + vec3(0.0f, 0.75f, 0.0f), vec3(1.6f, 0.06f, 1.0f)));
    for (int i = 0; i < 4; ++i) {
      const float sx = (i & 1) ? 1.0f : -1.0f, sz = (i & 2) ? 1.0f : -1.0f;
      add_box(table, box_transform(c + vec3(sx * 0.70f, 0.36f, sz * 0.42f), vec3(0.05f, 0.72f, 0.05f)));
    }
  }

  // Ramp: a 2.0 (x) × 0.04 × 1.6 m slab tilted 40° about x so that it rises towards -z; centre
  // (-2.5, 0.53, 1.5): it spans x in [-3.5, -1.5], z ≈ [0.89, 2.11], y ≈ [0, 1.04] (its low
  // edge rests on the floor). Its top's normal (0, 0.77, 0.64) faces the camera but nearly
  // grazes the light (N·L ≈ 0.08–0.14 over the top); the pole's shadow crosses it (light face
  // -x).
  add_box(new_mesh(s, "ramp", vec3(0.60f, 0.65f, 0.50f)),
          box_transform(vec3(-2.5f, 0.53f, 1.5f), vec3(2.0f, 0.04f, 1.6f), 40.0f, vec3(1, 0, 0)));

  // Light: off-centre, inside the room; far bounds the room diagonal (√(10² + 4² + 10²) ≈
  // 14.7 m).
  s.light.position = vec3(0.9f, 2.7f, -0.4f);
  s.light.radius = 0.03f;
  s.light.near = 0.05f;
  s.light.far = 20.0f;

  // Camera: near the south wall at (1.0, 2.5, 4.8), looking down towards (-1.0, 0.3, -1.0);
  // sees the floor, the north and west walls, every occluder and the shadows of the box
  // (behind it), the pole (across floor and ramp), the sphere (towards the camera) and the
  // table (under it).
  s.camera.eye = vec3(1.0f, 2.5f, 4.8f);
  s.camera.target = vec3(-1.0f, 0.3f, -1.0f);
  s.camera.up = vec3(0.0f, 1.0f, 0.0f);
  s.camera.fov_y_deg = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 30.0f;
  s.camera.width = 1024;
  s.camera.height = 768;
  return s;
}

// One 10 × 10 m floor quad at y = 0 centred on the origin (8 × 8 grid, front +y); light 2 m
// above its centre; camera 8 m above looking straight down (image x = world +x, image y down =
// world +z). Every floor point is lit (N·L > 0, nothing occludes).
Scene make_plane_scene() {
  Scene s;
  s.name = "plane";
  add_grid_quad(new_mesh(s, "floor", vec3(0.75f)), vec3(-5, 0, -5), vec3(0, 0, 10), vec3(10, 0, 0),
                8, 8);
  s.light.position = vec3(0.0f, 2.0f, 0.0f);
  s.light.radius = 0.03f;
  s.light.near = 0.05f;
  s.light.far = 20.0f;  // the farthest floor corner is √(50 + 4) ≈ 7.3 m away
  s.camera.eye = vec3(0.0f, 8.0f, 0.0f);
  s.camera.target = vec3(0.0f);
  s.camera.up = vec3(0.0f, 0.0f, -1.0f);
  s.camera.fov_y_deg = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 30.0f;
  return s;
}

}  // namespace shadowlab
