#include "techniques/cube_faces.h"

#include <cmath>

namespace shadowlab {
namespace {

// Forward (view -z) and up axes of each face, in world space.
const vec3 kForward[kCubeFaces] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const vec3 kUp[kCubeFaces] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

// right = forward × up (the view-space +x axis of lookAt).
const vec3 kRight[kCubeFaces] = {glm::cross(kForward[0], kUp[0]), glm::cross(kForward[1], kUp[1]),
                                 glm::cross(kForward[2], kUp[2]), glm::cross(kForward[3], kUp[3]),
                                 glm::cross(kForward[4], kUp[4]), glm::cross(kForward[5], kUp[5])};

}  // namespace

vec2 cube_face_uv(int face, const vec3& dir) {
  const float inv = 1.0f / glm::dot(dir, kForward[face]);
  return vec2(glm::dot(dir, kRight[face]) * inv, glm::dot(dir, kUp[face]) * inv);
}

int cube_face_of(const vec3& d) {
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  if (ax >= ay && ax >= az) return d.x >= 0.0f ? 0 : 1;
  if (ay >= az) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}

mat4 cube_face_view(const PointLight& light, int face) {
  return glm::lookAtRH(light.position, light.position + kForward[face], kUp[face]);
}

mat4 cube_face_projection(const PointLight& light) {
  return glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, light.near, light.far);
}

vec3 cube_face_direction(int face, float u, float v) {
  // View space: x right, y up, looking down -z; tan(45°) = 1 so NDC maps straight to slopes.
  const vec3 f = kForward[face], up = kUp[face];
  const vec3 right = glm::cross(f, up);
  return glm::normalize(f + u * right + v * up);
}

}  // namespace shadowlab
