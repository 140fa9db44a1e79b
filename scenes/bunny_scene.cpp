#include "scenes/bunny_scene.h"

#include "core/assets.h"
#include "scenes/mesh_builders.h"
#include "scenes/obj_loader.h"

namespace shadowlab {

Scene make_bunny_scene(std::vector<std::string>* notes) {
  const std::string path = asset_path("bunny/stanford-bunny.obj", "--scene bunny");
  Scene s = load_obj_scene(path, notes);
  s.name = "bunny";
  SL_CHECK_EQ(s.meshes.size(), size_t(1));
  s.meshes[kBunnyMesh].name = "bunny";
  s.materials[size_t(s.meshes[kBunnyMesh].material)].albedo = vec3(0.8f);
  Bounds b;
  for (const vec3& p : s.meshes[kBunnyMesh].positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  const vec3 c = b.centre();
  const float wall_z = b.lo.z - 0.06f;
  const float front_z = c.z + 0.5f;
  add_grid_quad(new_mesh(s, "ground", vec3(0.7f)), vec3(c.x - 0.4f, b.lo.y, wall_z),
                vec3(0.0f, 0.0f, front_z - wall_z), vec3(0.8f, 0.0f, 0.0f), 8, 8);
  add_grid_quad(new_mesh(s, "wall", vec3(0.7f)), vec3(c.x - 0.4f, b.lo.y, wall_z),
                vec3(0.8f, 0.0f, 0.0f), vec3(0.0f, 0.4f, 0.0f), 8, 4);

  s.camera.eye = c + vec3(0.0f, 0.04f, 0.50f);
  s.camera.target = c;
  s.camera.up = vec3(0.0f, 1.0f, 0.0f);
  s.camera.fov_y_deg = 30.0f;
  s.camera.near = 0.05f;
  s.camera.far = 5.0f;
  s.camera.width = 1024;
  s.camera.height = 768;

  s.light.position = c + vec3(-0.15f, 0.20f, 0.40f);
  s.light.radius = 0.003f;
  s.light.near = 0.005f;
  s.light.far = 1.5f;  // the farthest scene corner is ~1.0 m from the light

  s.projector.posed = true;
  s.projector.position = s.light.position;
  s.projector.direction = c - s.light.position;
  s.projector.up = vec3(0.0f, 1.0f, 0.0f);
  s.projector.fov_y_deg = 36.0f;
  s.projector.aspect = 1.0f;
  return s;
}

}  // namespace shadowlab
