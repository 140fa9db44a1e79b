// The hard-case suite's own scenes (scenes/hard_scenes.h): grazing, contact, depth_range.
#include "scenes/hard_scenes.h"

#include <cmath>

#include "scenes/mesh_builders.h"

namespace shadowlab {
namespace {

// A chain-link pattern: wires along both diagonals of each cell of an n × n grid over the
// texture, `wire` (fraction of a cell) wide; alpha 1 on the wires, 0 in the holes. RGBA, planar.
ImageF chain_link_texture(int size, int cells, float wire) {
  ImageF t(size, size, 4, 0.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size) * float(cells);
      const float v = (float(y) + 0.5f) / float(size) * float(cells);
      auto near_integer = [&](float s) { return std::fabs(s - std::round(s)) < 0.5f * wire; };
      const bool on_wire = near_integer(u + v) || near_integer(u - v);
      for (int c = 0; c < 3; ++c) t.at(x, y, c) = 0.55f;
      t.at(x, y, 3) = on_wire ? 1.0f : 0.0f;
    }
  return t;
}

}  // namespace

Scene make_grazing_scene() {
  Scene s;
  s.name = "grazing";
  // A 40 × 12 m floor along x; the light 0.6 m above its −x end, so the floor is lit at
  // 0.9°–6° and every post and slat casts a shadow metres long.
  add_grid_quad(new_mesh(s, "floor", vec3(0.72f)), vec3(-20, 0, -6), vec3(0, 0, 12),
                vec3(40, 0, 0), 32, 8);
  Mesh& posts = new_mesh(s, "posts", vec3(0.45f, 0.35f, 0.25f));
  for (int i = 0; i < 10; ++i) {
    const float x = -14.0f + 3.0f * float(i);
    add_box(posts, box_transform(vec3(x, 0.6f, -2.5f), vec3(0.1f, 1.2f, 0.1f)));
    add_box(posts, box_transform(vec3(x + 1.5f, 0.45f, 2.5f), vec3(0.08f, 0.9f, 0.08f), 30.0f));
  }
  // A fence of 60 slats 2 cm thick, 15 cm apart, across the light's view at x = −6 m: thin
  // occluders whose shadows are thin stripes kilometre-long in texel terms.
  Mesh& fence = new_mesh(s, "fence", vec3(0.6f, 0.5f, 0.4f));
  for (int i = 0; i < 60; ++i)
    add_box(fence, box_transform(vec3(-6.0f, 0.4f, -4.5f + 0.15f * float(i)), vec3(0.02f, 0.8f, 0.05f)));
  add_box(fence, box_transform(vec3(-6.0f, 0.82f, 0.0f), vec3(0.03f, 0.04f, 9.0f)));  // the top rail
  s.light.position = vec3(-19.0f, 0.6f, 0.3f);
  s.light.radius = 0.02f;
  s.light.near = 0.05f;
  s.light.far = 45.0f;
  s.camera.eye = vec3(-9.0f, 5.0f, 9.0f);
  s.camera.target = vec3(2.0f, 0.0f, 0.0f);
  s.camera.fov_y_deg = 55.0f;
  s.camera.near = 0.05f;
  s.camera.far = 80.0f;
  return s;
}

Scene make_contact_scene() {
  Scene s;
  s.name = "contact";
  add_grid_quad(new_mesh(s, "floor", vec3(0.75f)), vec3(-3, 0, -3), vec3(0, 0, 6), vec3(6, 0, 0),
                8, 8);
  add_grid_quad(new_mesh(s, "wall", vec3(0.7f, 0.68f, 0.62f)), vec3(-3, 0, -2), vec3(6, 0, 0),
                vec3(0, 2.5f, 0), 8, 4);
  // A chair whose 3 cm legs touch the floor (contact shadows, peter-panning).
  Mesh& chair = new_mesh(s, "chair", vec3(0.55f, 0.38f, 0.22f));
  for (int i = 0; i < 4; ++i) {
    const float x = (i & 1) ? 0.2f : -0.2f, z = (i & 2) ? 0.2f : -0.2f;
    add_box(chair, box_transform(vec3(-0.8f + x, 0.225f, 0.3f + z), vec3(0.03f, 0.45f, 0.03f)));
  }
  add_box(chair, box_transform(vec3(-0.8f, 0.465f, 0.3f), vec3(0.46f, 0.03f, 0.46f)));
  add_box(chair, box_transform(vec3(-0.8f, 0.75f, 0.085f), vec3(0.46f, 0.55f, 0.03f)));
  // A box resting on the floor and another leaning against it (touching occluders).
  Mesh& boxes = new_mesh(s, "boxes", vec3(0.4f, 0.5f, 0.65f));
  add_box(boxes, box_transform(vec3(0.7f, 0.2f, 0.6f), vec3(0.4f, 0.4f, 0.4f), 20.0f));
  add_box(boxes, box_transform(vec3(1.15f, 0.1f, 0.9f), vec3(0.3f, 0.2f, 0.3f), -10.0f));
  // A wire 4 mm thick strung 1.2 m above the floor (the thinnest occluder).
  Mesh& wire = new_mesh(s, "wire", vec3(0.2f));
  {
    Mesh w;
    add_cylinder(w, vec3(0.0f), 0.002f, 4.0f, 8);
    // Lay the cylinder (+y axis) along x, centred at (0, 1.2, 0.2).
    const mat4 m = glm::rotate(glm::translate(mat4(1.0f), vec3(-2.0f, 1.2f, 0.2f)),
                               glm::radians(-90.0f), vec3(0, 0, 1));
    for (vec3& p : w.positions) p = vec3(m * glm::vec4(p, 1.0f));
    for (vec3& n : w.normals) n = glm::normalize(vec3(m * glm::vec4(n, 0.0f)));
    const uint32_t base = uint32_t(wire.positions.size());
    wire.positions.insert(wire.positions.end(), w.positions.begin(), w.positions.end());
    wire.normals.insert(wire.normals.end(), w.normals.begin(), w.normals.end());
    for (uint32_t i : w.indices) wire.indices.push_back(base + i);
  }
  // A chain-link fence card 1.5 × 1.2 m with an alpha texture (4 cm holes, 6 mm wires), standing
  // on the floor in front of the wall.
  s.textures.push_back(chain_link_texture(256, 8, 0.15f));
  Material fence_material;
  fence_material.name = "chain_link";
  fence_material.albedo = vec3(0.55f);
  fence_material.alpha_texture = int(s.textures.size()) - 1;
  fence_material.alpha_cutoff = 0.5f;
  s.materials.push_back(fence_material);
  Mesh card;
  card.name = "chain_link";
  card.material = int(s.materials.size()) - 1;
  const vec3 o(0.2f, 0.0f, -1.2f), eu(1.5f, 0.0f, 0.0f), ev(0.0f, 1.2f, 0.0f);
  card.positions = {o, o + eu, o + eu + ev, o + ev};
  card.normals.assign(4, vec3(0, 0, 1));
  // 4 × 3.2 repeats of the 8-cell texture: cells 4.7 cm wide.
  card.uvs = {vec2(0, 0), vec2(4, 0), vec2(4, 3.2f), vec2(0, 3.2f)};
  card.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(card);
  s.light.position = vec3(0.6f, 2.2f, 1.6f);
  s.light.radius = 0.02f;
  s.light.near = 0.02f;
  s.light.far = 8.0f;
  s.camera.eye = vec3(0.4f, 1.7f, 3.2f);
  s.camera.target = vec3(0.0f, 0.4f, 0.0f);
  s.camera.fov_y_deg = 55.0f;
  s.camera.near = 0.05f;
  s.camera.far = 20.0f;
  return s;
}

Scene make_depth_range_scene() {
  Scene s;
  s.name = "depth_range";
  // A 2.4 km ground with boxes at 1, 10, 100 and 1000 m from the light, each sized with its
  // distance (a tenth of it), so the map's depth precision, not the texel size, decides.
  add_grid_quad(new_mesh(s, "ground", vec3(0.7f)), vec3(-1200, 0, -1200), vec3(0, 0, 2400),
                vec3(2400, 0, 0), 48, 48);
  Mesh& boxes = new_mesh(s, "boxes", vec3(0.45f, 0.5f, 0.6f));
  for (int i = 0; i < 4; ++i) {
    const float d = std::pow(10.0f, float(i));
    add_box(boxes, box_transform(vec3(d, 0.05f * d, -0.02f * d), vec3(0.1f * d), 25.0f));
  }
  s.light.position = vec3(0.0f, 0.5f, 0.0f);
  s.light.radius = 0.0f;
  s.light.near = 0.01f;  // 1 cm
  s.light.far = 1800.0f;
  s.camera.eye = vec3(-1.5f, 1.2f, 1.0f);
  s.camera.target = vec3(20.0f, 0.0f, -0.5f);
  s.camera.fov_y_deg = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 3000.0f;
  return s;
}

}  // namespace shadowlab
