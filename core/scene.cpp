#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/light_fit.h"

namespace shadowlab {

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangle_count();
  return n;
}

Bounds scene_bounds(const Scene& scene) {
  Bounds b;
  for (const Mesh& m : scene.meshes)
    for (const vec3& p : m.positions) {
      b.lo = glm::min(b.lo, p);
      b.hi = glm::max(b.hi, p);
    }
  return b;
}

float farthest_corner_distance(const Bounds& b, const vec3& from) {
  float reach = 0.0f;
  for (int i = 0; i < 8 && b.valid(); ++i) {
    const vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
    reach = std::max(reach, glm::length(corner - from));
  }
  return reach;
}

void compute_vertex_normals(Mesh& mesh) {
  std::vector<vec3> acc(mesh.positions.size(), vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    // Cross product length is twice the area: the sum is area-weighted.
    const vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a],
                              mesh.positions[c] - mesh.positions[a]);
    acc[a] += n;
    acc[b] += n;
    acc[c] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t i = 0; i < acc.size(); ++i) {
    const float len = glm::length(acc[i]);
    mesh.normals[i] = len > 0.0f ? acc[i] / len : vec3(0.0f, 1.0f, 0.0f);
  }
}

void validate_scene(const Scene& scene, const std::string& where) {
  for (const Mesh& m : scene.meshes) {
    for (size_t i = 0; i < m.positions.size(); ++i)
      if (!is_finite(m.positions[i]))
        throw InputError(where, "mesh '" + m.name + "' vertex " + std::to_string(i) +
                                    " has a NaN or infinite coordinate");
    if (m.indices.size() % 3 != 0)
      throw InputError(where, "mesh '" + m.name + "' index count is not a multiple of 3");
    for (uint32_t idx : m.indices)
      if (idx >= m.positions.size())
        throw InputError(where, "mesh '" + m.name + "' index " + std::to_string(idx) +
                                    " is out of range");
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
      throw InputError(where, "mesh '" + m.name + "' normal count differs from vertex count");
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
      throw InputError(where, "mesh '" + m.name + "' uv count differs from vertex count");
    if (m.material < 0 || size_t(m.material) >= scene.materials.size())
      throw InputError(where, "mesh '" + m.name + "' has no valid material");
    if (scene.materials[size_t(m.material)].alpha_texture >= 0 && m.uvs.empty() &&
        m.triangle_count() > 0)
      throw InputError(where, "mesh '" + m.name + "' uses the alpha-textured material '" +
                                  scene.materials[size_t(m.material)].name +
                                  "' but has no texture coordinates");
  }
  for (const Material& mat : scene.materials) {
    if (mat.alpha_texture >= int(scene.textures.size()))
      throw InputError(where, "material '" + mat.name + "' refers to a missing texture");
    if (mat.alpha_texture >= 0 && (scene.textures[size_t(mat.alpha_texture)].channels != 4 ||
                                   scene.textures[size_t(mat.alpha_texture)].empty()))
      throw InputError(where, "material '" + mat.name + "': its alpha texture is not a non-empty RGBA image");
    if (mat.color_texture >= int(scene.textures.size()) ||
        (mat.color_texture >= 0 && (scene.textures[size_t(mat.color_texture)].channels != 4 ||
                                    scene.textures[size_t(mat.color_texture)].empty())))
      throw InputError(where, "material '" + mat.name + "': its colour texture is not a non-empty RGBA image");
    if (!(mat.alpha_cutoff >= 0.0f && mat.alpha_cutoff <= 1.0f))
      throw InputError(where, "material '" + mat.name + "': alpha cutoff must lie in [0, 1]");
  }
  const PointLight& l = scene.light;
  if (!is_finite(l.position) || !std::isfinite(l.radius) || l.radius < 0.0f)
    throw InputError(where, "light position must be finite and radius >= 0");
  if (!(l.near > 0.0f) || !(l.far > l.near) || !std::isfinite(l.far))
    throw InputError(where, "light near/far must satisfy 0 < near < far < inf");
  if (const LightFitProblem fit = light_fit_problem(scene); fit.kind != LightFitProblem::None)
    throw InputError(where, fit.reason);
  if (scene.projector.enabled) {
    validate_projector(scene.projector, where);
    if (glm::length(scene.projector.position - l.position) > 1e-5f * (1.0f + glm::length(l.position)) ||
        l.radius != 0.0f)
      throw InputError(where, "a projector scene's point light must sit at the projector with radius 0");
  }
  const Camera& c = scene.camera;
  if (!is_finite(c.eye) || !is_finite(c.target) || !is_finite(c.up))
    throw InputError(where, "camera eye/target/up must be finite");
  if (glm::length(c.target - c.eye) <= 0.0f)
    throw InputError(where, "camera eye and target coincide");
  if (glm::length(glm::cross(c.target - c.eye, c.up)) <= 0.0f)
    throw InputError(where, "camera up is parallel to the view direction");
  if (!(c.fov_y_deg > 0.0f && c.fov_y_deg < 179.0f))
    throw InputError(where, "camera fov must lie in (0, 179) degrees");
  if (!(c.near > 0.0f) || !(c.far > c.near))
    throw InputError(where, "camera near/far must satisfy 0 < near < far");
  if (c.width < 1 || c.height < 1 || c.width > kMaxImageSide || c.height > kMaxImageSide)
    throw InputError(where, "image size " + std::to_string(c.width) + "x" +
                                std::to_string(c.height) + " is outside [1, " +
                                std::to_string(kMaxImageSide) + "]");
}

mat4 camera_view(const Camera& camera) {
  return glm::lookAtRH(camera.eye, camera.target, camera.up);
}

mat4 camera_projection(const Camera& camera) {
  return glm::perspectiveRH_NO(glm::radians(camera.fov_y_deg),
                               float(camera.width) / float(camera.height), camera.near,
                               camera.far);
}

}  // namespace shadowlab
