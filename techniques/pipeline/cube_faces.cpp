#include "techniques/pipeline/cube_faces.h"

#include <cmath>

namespace shadowlab {
mat4 cube_face_view(const PointLight& light, int face) {
  return glm::lookAtRH(light.position, light.position + kCubeForward[face], kCubeUp[face]);
}

mat4 cube_face_projection(const PointLight& light) {
  return glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, light.near, light.far);
}

vec3 cube_face_direction(int face, float u, float v) {
  // View space: x right, y up, looking down -z; tan(45°) = 1 so NDC maps straight to slopes.
  const vec3 f = kCubeForward[face], up = kCubeUp[face];
  const vec3 right = glm::cross(f, up);
  return glm::normalize(f + u * right + v * up);
}

}  // namespace shadowlab
