#include "scenes/scene_library.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/light_fit.h"
#include "core/parse_number.h"
#include "scenes/mesh_builders.h"
#include "scenes/obj_loader.h"

namespace shadowlab {

void frame_from_bounds(Scene& s, bool camera, bool light, const std::string& where) {
  const Bounds b = scene_bounds(s);
  const vec3 c = b.centre();
  float r = 0.5f * glm::length(b.extent());
  if (!(r > 0.0f)) r = 1.0f;  // a single point: any scale will do
  // The automatic framing puts the camera and light a few radii away: with coordinates near
  // float's limit that overflows (then the light, which the user never set, would be named).
  if ((camera || light) &&
      !(std::isfinite(r) && is_finite(c) && r < 1e30f && glm::length(c) < 1e30f)) {
    double largest = 0.0;
    for (int k = 0; k < 3; ++k)
      largest = std::max({largest, std::fabs(double(b.lo[k])), std::fabs(double(b.hi[k]))});
    throw InputError(where, "the model's bounds are too large to frame a camera and a light "
                            "automatically (coordinates up to " + number_text(largest) +
                                " m); scale the model or give them in the file");
  }
  // Every triangle of zero area: nothing casts or receives a shadow.
  bool any_area = false;
  for (const Mesh& m : s.meshes)
    for (size_t t = 0; t < m.triangle_count() && !any_area; ++t) {
      const vec3 a = m.positions[m.indices[3 * t]], b2 = m.positions[m.indices[3 * t + 1]],
                 c2 = m.positions[m.indices[3 * t + 2]];
      any_area = glm::length(glm::cross(b2 - a, c2 - a)) > 0.0f;
    }
  if (!any_area)
    throw InputError(where, "every triangle has zero area: nothing to render or shadow");
  if (camera) {
    const float d = 1.05f * r / std::sin(glm::radians(30.0f));
    s.camera.eye = c + d * glm::normalize(vec3(0.0f, 1.0f, 1.0f));
    s.camera.target = c;
    s.camera.up = vec3(0.0f, 1.0f, 0.0f);
    s.camera.fov_y_deg = 60.0f;
    s.camera.near = std::max(0.5f * (d - r), 1e-3f * d);
    s.camera.far = 1.5f * (d + r);
  }
  if (light) {
    s.light.position = c + 1.5f * r * glm::normalize(vec3(1.0f, 1.5f, 0.5f));
    s.light.radius = 0.01f * r;
    s.light.far = 1.02f * 2.5f * r;
    s.light.near = 1e-3f * s.light.far;
  }
}

Scene make_obj_scene(const std::string& obj_path, std::vector<std::string>* notes) {
  Scene s = load_obj_scene(obj_path, notes);
  const ObjViewHeader header = read_obj_view_header(obj_path);
  frame_from_bounds(s, !header.camera, !header.light, obj_path);
  if (header.camera) s.camera = *header.camera;
  if (header.light) s.light = *header.light;
  validate_scene(s, obj_path);
  return s;
}

void apply_camera_size(Scene& scene, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw InputError("--size", std::to_string(width) + "x" + std::to_string(height) +
                                   " is outside [1, " + std::to_string(kMaxImageSide) + "]");
  scene.camera.width = width;
  scene.camera.height = height;
}

void add_ground_plane(Scene& scene, float size_factor) {
  const Bounds b = scene_bounds(scene);
  SL_CHECK(b.valid() && size_factor > 0.0f);
  const float side = std::max(size_factor * glm::length(b.extent()), 1e-3f);
  const vec3 c = b.centre();
  const vec3 origin(c.x - 0.5f * side, b.lo.y, c.z - 0.5f * side);
  add_grid_quad(new_mesh(scene, "ground", vec3(0.7f)), origin, vec3(0, 0, side), vec3(side, 0, 0),
                8, 8);
  // Reach the farthest ground corner from the light.
  float reach = 0.0f;
  for (int i = 0; i < 4; ++i) {
    const vec3 corner = origin + vec3((i & 1) ? side : 0.0f, 0.0f, (i & 2) ? side : 0.0f);
    reach = std::max(reach, glm::length(corner - scene.light.position));
  }
  scene.light.far = std::max(scene.light.far, 1.02f * reach);
}

void set_projector(Scene& scene, Projector projector, const std::string& where) {
  projector.enabled = true;
  validate_projector(projector, where);
  scene.projector = std::move(projector);
  scene.light.position = scene.projector.position;
  scene.light.radius = 0.0f;
  cover_scene_with_light_range(scene);
}

}  // namespace shadowlab
