#include "scenes/foliage_scene.h"

#include <algorithm>

#include "core/assets.h"
#include "scenes/mesh_builders.h"
#include "scenes/obj_loader.h"
#include "scenes/scene_merge.h"

namespace shadowlab {

Scene make_foliage_scene(std::vector<std::string>* notes) {
  const char* where = "--scene foliage";
  Scene s;
  s.name = "foliage";
  add_grid_quad(new_mesh(s, "ground", vec3(0.55f, 0.5f, 0.42f)), vec3(-4.5f, 0.0f, -2.2f),
                vec3(0.0f, 0.0f, 7.0f), vec3(9.0f, 0.0f, 0.0f), 12, 12);
  add_grid_quad(new_mesh(s, "wall", vec3(0.75f)), vec3(-4.5f, 0.0f, -2.2f), vec3(9.0f, 0.0f, 0.0f),
                vec3(0.0f, 4.5f, 0.0f), 12, 6);
  struct Placement {
    const char* asset;
    vec3 at;
  };
  const Placement plants[] = {
      {"palm_tree/palm_tree.obj", {-0.7f, 0.0f, -0.9f}},
      {"plants/shrub.obj", {1.6f, 0.0f, -1.2f}},
      {"plants/shrub_red.obj", {2.6f, 0.0f, 0.9f}},
      {"plants/parviflora.obj", {0.5f, 0.0f, 1.0f}},
      {"plants/fern3.obj", {-2.6f, 0.22f, 0.7f}},
  };
  for (const Placement& p : plants) {
    Scene plant = load_obj_scene(asset_path(p.asset, where), notes);
    // Centimetres to metres, then placed (a uniform positive scale: normals unchanged).
    for (Mesh& m : plant.meshes)
      for (vec3& q : m.positions) q = q * 0.01f + p.at;
    append_scene(s, std::move(plant));
  }

  s.light.position = vec3(2.5f, 5.5f, 4.5f);
  s.light.radius = 0.0f;
  s.light.near = 0.05f;
  s.light.far = 1.02f * farthest_corner_distance(scene_bounds(s), s.light.position);

  s.camera.eye = vec3(0.0f, 2.4f, 7.2f);
  s.camera.target = vec3(0.0f, 1.5f, -0.6f);
  s.camera.up = vec3(0.0f, 1.0f, 0.0f);
  s.camera.fov_y_deg = 50.0f;
  s.camera.near = 0.1f;
  s.camera.far = 40.0f;
  s.camera.width = 1024;
  s.camera.height = 768;
  return s;
}

}  // namespace shadowlab
