#pragma once
// The slide projector (Dowling): a spot light at `position` looking along `direction` that
// casts a slide through a perspective frustum. World space, metres.
//
// Projector space: forward = normalize(direction), right = normalize(forward × up),
// up' = right × forward. A point p with d = p − position and depth z = d·forward > 0 lands on
// the slide at
//   s = ½ + ½·(d·right)/(z·tan(fov_x/2)),   t = ½ − ½·(d·up')/(z·tan(fov_y/2)),
// tan(fov_x/2) = aspect·tan(fov_y/2) (aspect = slide width / height). Computing s, t from the
// world position of each surface point is the perspective-correct projective texture lookup
// (no interpolation of s, t across triangles). Points with z <= 0 (behind the projector, or in
// its plane) and points with s or t outside [0, 1] receive no light. The near plane does not
// clip the light (it only bounds the shadow map's depth range).
#include <string>

#include "core/math.h"
#include "core/slide.h"

namespace shadowlab {

struct Projector {
  bool enabled = false;              // false: the scene's light is a plain point light
  bool posed = false;                // a scene builder chose the pose below (else --slide aims
                                     // from the scene's light at the camera target)
  vec3 position{0.0f, 2.0f, 2.0f};   // metres
  vec3 direction{0.0f, 0.0f, -1.0f}; // any length > 0
  vec3 up{0.0f, 1.0f, 0.0f};         // not parallel to direction
  float fov_y_deg = 40.0f;           // vertical field of view, (0, 170) degrees
  float aspect = 1.0f;               // slide width / height, [0.05, 20]
  Slide slide;
};

// Orthonormal projector frame (see the top of this file).
struct ProjectorFrame {
  vec3 forward, right, up;
  float tan_x, tan_y;  // tangents of the half fields of view
};
ProjectorFrame projector_frame(const Projector& proj);

// Slide coordinates of world point p; false when p is behind the projector or outside its
// frustum (then st is unspecified).
bool projector_slide_coords(const ProjectorFrame& frame, const vec3& position, const vec3& p,
                            vec2& st);
// The slide's linear RGB at p: sample_slide at p's slide coordinates, 0 where p receives no
// light.
vec3 projector_light(const Projector& proj, const ProjectorFrame& frame, const vec3& p);

// Throws InputError(where, reason) unless the projector is usable: finite vectors, non-zero
// direction, up not parallel to it, fov and aspect in range, a non-empty slide.
void validate_projector(const Projector& proj, const std::string& where);

}  // namespace shadowlab
