#pragma once
// The six faces of a cube shadow map around a point light.
//
// Face order: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (world axes). A direction belongs to the face
// of its major axis; ties break towards the lower axis (x before y before z) and a zero
// component counts as positive — one rule shared by rendering and lookup. Each face is a
// 90° square perspective frustum; its texel (x, y) is row-major with y down, like every image.
#include <array>
#include <cmath>

#include "core/math.h"
#include "core/scene.h"

namespace shadowlab {

constexpr int kCubeFaces = 6;

// Forward (view -z), up and right (= forward × up, the view +x) axes of each face, world space.
inline const vec3 kCubeForward[kCubeFaces] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                              {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline const vec3 kCubeUp[kCubeFaces] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                         {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
// Written out (glm::cross's bits, signed zeros included: CubeFaces.RightIsForwardCrossUpBitForBit)
// so that every table is constant-initialized: a dynamic initializer in a header that AVX2 files
// include would be compiled for AVX2 and run at load time on any CPU.
inline const vec3 kCubeRight[kCubeFaces] = {{0, 0, -1}, {0, 0, 1},        {1, 0, 0},
                                            {1, 0, 0},  {1, 0, -0.0f},    {-1, -0.0f, -0.0f}};

// Face of a (non-zero) direction from the light. (Inline: it runs once per lookup.)
inline int cube_face_of(const vec3& d) {
  const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  if (ax >= ay && ax >= az) return d.x >= 0.0f ? 0 : 1;
  if (ay >= az) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}
// World → face view matrix (light at the origin of view space, looking down -z).
mat4 cube_face_view(const PointLight& light, int face);
// Face projection: 90° square frustum between the light's near and far planes.
mat4 cube_face_projection(const PointLight& light);
// Face coordinates (u, v) in NDC of a direction from the light, without the projection matrix:
// u = dir·right / dir·forward, v = dir·up / dir·forward (the same mapping as
// cube_face_projection() · cube_face_view(), up to rounding).
inline vec2 cube_face_uv(int face, const vec3& dir) {
  const float inv = 1.0f / glm::dot(dir, kCubeForward[face]);
  return vec2(glm::dot(dir, kCubeRight[face]) * inv, glm::dot(dir, kCubeUp[face]) * inv);
}
// Unit world-space direction through face coordinates (u, v) in NDC ([-1,1] covers the face,
// values outside it continue the face's plane).
vec3 cube_face_direction(int face, float u, float v);

}  // namespace shadowlab
