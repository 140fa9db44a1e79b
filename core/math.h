#pragma once
// GLM aliases used across shadowlab. World space: right-handed, y up, metres.
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace shadowlab {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;
using ivec2 = glm::ivec2;
using mat4 = glm::mat4;

// True when every component is finite (no NaN, no Inf).
inline bool is_finite(const vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace shadowlab
