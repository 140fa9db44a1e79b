#pragma once
// The six faces of a cube shadow map around a point light.
//
// Face order: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (world axes). A direction belongs to the face
// of its major axis; ties break towards the lower axis (x before y before z) and a zero
// component counts as positive — one rule shared by rendering and lookup. Each face is a
// 90° square perspective frustum; its texel (x, y) is row-major with y down, like every image.
#include <array>

#include "core/math.h"
#include "core/scene.h"

namespace shadowlab {

constexpr int kCubeFaces = 6;

// Face of a (non-zero) direction from the light.
int cube_face_of(const vec3& dir);
// World → face view matrix (light at the origin of view space, looking down -z).
mat4 cube_face_view(const PointLight& light, int face);
// Face projection: 90° square frustum between the light's near and far planes.
mat4 cube_face_projection(const PointLight& light);
// Face coordinates (u, v) in NDC of a direction from the light, without the projection matrix:
// u = dir·right / dir·forward, v = dir·up / dir·forward (the same mapping as
// cube_face_projection() · cube_face_view(), up to rounding).
vec2 cube_face_uv(int face, const vec3& dir);
// Unit world-space direction through face coordinates (u, v) in NDC ([-1,1] covers the face,
// values outside it continue the face's plane).
vec3 cube_face_direction(int face, float u, float v);

}  // namespace shadowlab
