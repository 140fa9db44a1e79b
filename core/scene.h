#pragma once
// Scene description shared by the rasterizer, the Embree reference and the techniques.
// World space: right-handed, y up, metres. Meshes, materials and textures refer to each other
// by index. Triangles are counter-clockwise seen from their front side.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "core/projector.h"

namespace shadowlab {

struct Material {
  std::string name;
  vec3 albedo{0.8f};          // linear diffuse colour
  int alpha_texture = -1;     // index into Scene::textures (RGBA; alpha in channel 3), -1: opaque
  float alpha_cutoff = 0.5f;  // a fragment with alpha < cutoff is discarded (both passes)
  // Colour texture (RGBA, linear; index into Scene::textures, -1: none): the albedo at a point
  // of a mesh with uvs is color_factor × its RGB there (core/texture.h sample_rgb), used by the
  // shaded pictures; `albedo` stays the mean colour (color_factor × the texture's mean).
  int color_texture = -1;
  vec3 color_factor{1.0f};
};

struct Mesh {
  std::string name;
  std::vector<vec3> positions;     // world space, metres
  std::vector<vec3> normals;       // per vertex, unit length; same count as positions
  std::vector<vec2> uvs;           // per vertex, or empty
  std::vector<uint32_t> indices;   // 3 per triangle
  int material = 0;                // index into Scene::materials

  size_t triangle_count() const { return indices.size() / 3; }
};

// Point light; radius > 0 makes it a sphere light for the soft reference.
struct PointLight {
  vec3 position{0.0f};
  float radius = 0.0f;  // metres; 0 = hard point light
  float near = 0.05f;   // metres; shadow-map near plane
  float far = 40.0f;    // metres; light range: stored radial distances are |p - L| / far
};

// Perspective camera. Looks from eye to target; fov_y in degrees.
struct Camera {
  vec3 eye{0.0f, 0.0f, 5.0f};
  vec3 target{0.0f};
  vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 60.0f;
  float near = 0.05f;
  float far = 100.0f;
  int width = 1024;
  int height = 768;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<ImageF> textures;   // RGBA, linear colour, alpha as stored
  PointLight light;
  // When projector.enabled, the light is a slide projector: `light` then sits at the
  // projector's position with radius 0 (set_projector in scenes/scene_library.h), so visibility
  // from it is what every technique and the reference compute, and a point outside the
  // projector's frustum receives no light (mask 0, technique.h).
  Projector projector;
  Camera camera;
  uint64_t seed = 1;              // scene seed for every stochastic choice (RNG streams)

  size_t triangle_count() const;
};

// Axis-aligned bounds of every vertex of the scene.
struct Bounds {
  vec3 lo{1e30f};
  vec3 hi{-1e30f};
  bool valid() const { return lo.x <= hi.x; }
  vec3 centre() const { return 0.5f * (lo + hi); }
  vec3 extent() const { return hi - lo; }
};
Bounds scene_bounds(const Scene& scene);
// Distance from `from` to the farthest of the 8 corners of b (0 for invalid bounds): a light
// range that covers every point of the box.
float farthest_corner_distance(const Bounds& b, const vec3& from);

// Fills missing per-vertex normals with area-weighted face normals.
void compute_vertex_normals(Mesh& mesh);

// Throws InputError(where, ...) if any vertex is NaN/Inf, an index is out of range, a material
// index is invalid, the light radius is negative, the light does not fit the scene
// (core/light_fit.h light_fit_problem), or the camera is degenerate/absurd.
void validate_scene(const Scene& scene, const std::string& where);

// Camera matrices: view (world → view, camera looks down -z) and OpenGL-style projection
// (clip z in [-w, w]).
mat4 camera_view(const Camera& camera);
mat4 camera_projection(const Camera& camera);

}  // namespace shadowlab
