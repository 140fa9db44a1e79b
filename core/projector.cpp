#include "core/projector.h"

#include <cmath>

#include "core/error.h"

namespace shadowlab {

ProjectorFrame projector_frame(const Projector& proj) {
  ProjectorFrame f;
  f.forward = glm::normalize(proj.direction);
  f.right = glm::normalize(glm::cross(f.forward, proj.up));
  f.up = glm::cross(f.right, f.forward);
  f.tan_y = float(std::tan(double(proj.fov_y_deg) * 3.14159265358979323846 / 360.0));
  f.tan_x = proj.aspect * f.tan_y;
  return f;
}

bool projector_slide_coords(const ProjectorFrame& frame, const vec3& position, const vec3& p,
                            vec2& st) {
  const vec3 d = p - position;
  const float z = glm::dot(d, frame.forward);
  if (!(z > 0.0f)) return false;
  st.x = 0.5f + 0.5f * glm::dot(d, frame.right) / (z * frame.tan_x);
  st.y = 0.5f - 0.5f * glm::dot(d, frame.up) / (z * frame.tan_y);
  return st.x >= 0.0f && st.x <= 1.0f && st.y >= 0.0f && st.y <= 1.0f;
}

vec3 projector_light(const Projector& proj, const ProjectorFrame& frame, const vec3& p) {
  vec2 st;
  if (!projector_slide_coords(frame, proj.position, p, st)) return vec3(0.0f);
  return sample_slide(proj.slide.rgb, st);
}

void validate_projector(const Projector& proj, const std::string& where) {
  if (!is_finite(proj.position) || !is_finite(proj.direction) || !is_finite(proj.up))
    throw InputError(where, "projector position/direction/up must be finite");
  if (!(glm::length(proj.direction) > 0.0f))
    throw InputError(where, "projector direction must be non-zero");
  const vec3 side = glm::cross(glm::normalize(proj.direction), proj.up);
  if (!(glm::length(side) > 1e-6f))
    throw InputError(where, "projector up is parallel to its direction");
  if (!(proj.fov_y_deg > 0.0f && proj.fov_y_deg < 170.0f))
    throw InputError(where, "projector fov must lie in (0, 170) degrees");
  if (!(proj.aspect >= 0.05f && proj.aspect <= 20.0f))
    throw InputError(where, "projector aspect must lie in [0.05, 20]");
  if (proj.slide.rgb.empty() || proj.slide.rgb.channels != 3)
    throw InputError(where, "projector has no slide");
}

}  // namespace shadowlab
