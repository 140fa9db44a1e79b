#include "techniques/pipeline/light_faces.h"

#include <algorithm>
#include <cmath>

#include "techniques/pipeline/cube_faces.h"

namespace shadowlab {

// (0, -1/√3, √(2/3)), (0, -1/√3, -√(2/3)), (-√(2/3), 1/√3, 0), (√(2/3), 1/√3, 0).
const vec3 kTetraNormals[4] = {
    {0.0f, -0.57735026919f, 0.81649658093f},
    {0.0f, -0.57735026919f, -0.81649658093f},
    {-0.81649658093f, 0.57735026919f, 0.0f},
    {0.81649658093f, 0.57735026919f, 0.0f},
};

namespace {

// Grows the owned rectangle by `guard` texels of an image `w` × `h` texels in all, keeping the
// owned part at (w - 2·guard) × (h - 2·guard) texels.
void set_extent(LightFace& f, float l, float r, float b, float t, int w, int h, int guard) {
  const float du = (r - l) / float(w - 2 * guard), dv = (t - b) / float(h - 2 * guard);
  f.left = l - float(guard) * du;
  f.right_edge = r + float(guard) * du;
  f.bottom = b - float(guard) * dv;
  f.top = t + float(guard) * dv;
  f.width = w;
  f.height = h;
}

}  // namespace

int tetra_atlas_size(int n) {
  const double target = 6.0 * double(n) * double(n);
  int s = 2 * int(std::floor(std::sqrt(target) / 2.0));
  if (s < 2) s = 2;
  // Even candidates s and s + 2 bracket √target; take the closer texel count (lower on a tie).
  const double below = std::fabs(double(s) * s - target);
  const double above = std::fabs(double(s + 2) * (s + 2) - target);
  return above < below ? s + 2 : s;
}

FaceLayout cube_layout(int res, int guard) {
  FaceLayout L;
  L.kind = FaceLayoutKind::Cube;
  L.res = res;
  L.guard = guard;
  L.faces.resize(kCubeFaces);
  for (int i = 0; i < kCubeFaces; ++i) {
    LightFace& f = L.faces[size_t(i)];
    f.forward = kCubeForward[i];
    f.up = kCubeUp[i];
    f.right = kCubeRight[i];
    set_extent(f, -1.0f, 1.0f, -1.0f, 1.0f, res + 2 * guard, res + 2 * guard, guard);
  }
  return L;
}

FaceLayout tetra_layout(int res, int guard) {
  FaceLayout L;
  L.kind = FaceLayoutKind::Tetrahedron;
  L.res = res;
  L.atlas = tetra_atlas_size(res);
  const int side = L.atlas / 2;
  // A face too small for its guard keeps at least one owned texel.
  L.guard = std::min(guard, (side - 1) / 2);
  const float s2 = std::sqrt(2.0f), s6 = std::sqrt(6.0f);
  L.faces.resize(4);
  for (int i = 0; i < 4; ++i) {
    LightFace& f = L.faces[size_t(i)];
    f.forward = kTetraNormals[i];
    // Up: towards the corner -normal[j] of the lowest other face j, made orthogonal to forward.
    const int j = i == 0 ? 1 : 0;
    const vec3 corner = -kTetraNormals[j];
    f.up = glm::normalize(corner - glm::dot(corner, f.forward) * f.forward);
    f.right = glm::cross(f.forward, f.up);
    // The owned triangle's tight box, grown by the guard.
    set_extent(f, -s6, s6, -s2, 2.0f * s2, side, side, L.guard);
  }
  return L;
}

int paraboloid_face_edge(int res) {
  return std::max(1, int(std::lround(std::sqrt(3.0) * double(res))));
}

FaceLayout dual_paraboloid_layout(int res, int guard) {
  FaceLayout L;
  L.kind = FaceLayoutKind::DualParaboloid;
  L.res = res;
  L.guard = guard;
  const int e = paraboloid_face_edge(res);
  L.faces.resize(2);
  for (int i = 0; i < 2; ++i) {
    LightFace& f = L.faces[size_t(i)];
    f.forward = vec3(0.0f, i == 0 ? -1.0f : 1.0f, 0.0f);
    f.up = vec3(0.0f, 0.0f, i == 0 ? 1.0f : -1.0f);
    f.right = glm::cross(f.forward, f.up);
    f.paraboloid = true;
    set_extent(f, -1.0f, 1.0f, -1.0f, 1.0f, e + 2 * guard, e + 2 * guard, guard);
  }
  return L;
}

FaceLayout projector_layout(const Projector& projector, int res, int guard) {
  FaceLayout L;
  L.kind = FaceLayoutKind::Projector;
  L.res = res;
  L.guard = guard;
  const ProjectorFrame fr = projector_frame(projector);
  LightFace f;
  f.forward = fr.forward;
  f.up = fr.up;
  f.right = fr.right;
  const int w = std::max(1, int(std::lround(double(res) * double(projector.aspect))));
  set_extent(f, -fr.tan_x, fr.tan_x, -fr.tan_y, fr.tan_y, w + 2 * guard, res + 2 * guard, guard);
  L.faces.push_back(f);
  return L;
}

vec3 face_texel_direction(const LightFace& f, float sx, float sy) {
  const float u = f.left + sx / float(f.width) * (f.right_edge - f.left);
  const float v = f.top - sy / float(f.height) * (f.top - f.bottom);
  if (f.paraboloid) {
    // Inverse of (u, v) = (x, y)/(1 + z) on the unit sphere.
    const float q = u * u + v * v;
    return glm::normalize(2.0f * u * f.right + 2.0f * v * f.up + (1.0f - q) * f.forward);
  }
  return glm::normalize(f.forward + u * f.right + v * f.up);
}

mat4 face_view_proj(const LightFace& f, const PointLight& light) {
  const mat4 view = glm::lookAtRH(light.position, light.position + f.forward, f.up);
  const float n = light.near;
  const mat4 proj =
      glm::frustumRH_NO(f.left * n, f.right_edge * n, f.bottom * n, f.top * n, n, light.far);
  return proj * view;
}

}  // namespace shadowlab
