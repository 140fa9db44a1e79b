#pragma once
// Face layouts of omnidirectional shadow maps around a point light, in one generic form used by
// the tetrahedral map and by the moment maps (VSM, ESM) on both layouts.
//
// A face is a perspective frustum from the light with its own view axes. Its image is
// width × height texels (row-major, y down, texel centres at +0.5) covering the rectangle
// [left, right] × [bottom, top] of the face's image plane at unit distance along `forward`
// (plane coordinates u = dir·right / dir·forward, v = dir·up / dir·forward). The rectangle
// includes a guard band of `guard` texels on every side beyond the region the face owns, so
// filters and PCF taps near a face boundary read real geometry rendered by this face (no
// cross-face lookups, no seams) as long as their reach is at most the guard.
//
// Cube: 6 faces, the order, axes and tie-break of techniques/pipeline/cube_faces.h; the owned region
// is the 90° square [-1, 1]², the image is (res + 2·guard)² texels.
// Tetrahedron: 4 faces with the light-space normals of docs/design.md §6, 109.47° apart; a direction
// belongs to argmax dot(dir, normal) (ties to the lower index). Each face owns a spherical
// triangle whose corners are the other three faces' negated normals (70.53° off axis); its
// gnomonic image is a triangle with circumradius 2√2, one corner along +up. The face's
// rectangle is that triangle's tight box, [-√6, √6] × [-√2, 2√2] (135.58° × 125.26°, an
// asymmetric frustum), plus the guard. The four faces are packed as the four quadrants of one
// S × S texture (face 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right), each face
// S/2 × S/2 square texels over a 1.155:1 rectangle, so texels are non-square. S is the even
// size whose texel count is closest to 6·N² for the comparable cube edge N (Kluczek).
// Dual paraboloid (Brabec, Annen & Seidel 2002): 2 faces, forward −y (the hemisphere below the
// light) and +y; a direction d̂ with z = d̂·forward >= 0 (ties to face 0) maps to the image-plane
// point (d̂·right, d̂·up)/(1 + z), the hemisphere filling the unit disk (a conformal map: a
// texel's angular size is plane texel × 2/(1 + u² + v²) in every direction). Each face's image
// is [-1, 1]² of E × E texels plus the guard, E = round(√3·N), so the two faces hold ~6·N²
// texels like the cube. Rendered through raster/paraboloid.h (per-vertex projection, linear
// interpolation between vertices).
// Projector: 1 face, the slide projector's frustum (core/projector.h): forward, up and right
// of its frame, the owned region [-tan_x, tan_x] × [-tan_y, tan_y], round(N·aspect) × N texels
// plus the guard. Every direction maps to face 0; directions outside the frustum receive no
// light and are never looked up.
#include <vector>

#include "core/math.h"
#include "core/scene.h"
#include "techniques/pipeline/cube_faces.h"

namespace shadowlab {

enum class FaceLayoutKind { Cube, Tetrahedron, Projector, DualParaboloid };

// Light-space normals of the four tetrahedral faces (unit vectors).
extern const vec3 kTetraNormals[4];

struct LightFace {
  vec3 forward{0.0f}, up{0.0f}, right{0.0f};  // world-space axes (view -z = forward)
  float left = -1.0f, right_edge = 1.0f;      // plane-coordinate extent in u, guard included
  float bottom = -1.0f, top = 1.0f;           // plane-coordinate extent in v, guard included
  int width = 0, height = 0;                  // texels, guard included
  bool paraboloid = false;                    // image-plane map of the dual-paraboloid layout
                                              // (u, v = (d̂·right, d̂·up)/(1 + d̂·forward))
                                              // instead of the gnomonic one
  size_t texel_count() const { return size_t(width) * size_t(height); }
};

struct FaceLayout {
  FaceLayoutKind kind = FaceLayoutKind::Cube;
  int res = 0;    // the spec's res: cube face edge N (for both kinds, the comparable cube edge)
  int guard = 0;  // guard texels on each side of every face
  int atlas = 0;  // tetrahedron: edge S of the packed texture; cube: 0
  std::vector<LightFace> faces;
};

// Cube layout: faces of (res + 2·guard)² texels.
FaceLayout cube_layout(int res, int guard);
// Tetrahedral layout for comparable cube edge `res`: faces of S/2 × S/2 texels, guard included.
FaceLayout tetra_layout(int res, int guard);
// Dual-paraboloid layout: 2 faces of (E + 2·guard)² texels, E = paraboloid_face_edge(res).
FaceLayout dual_paraboloid_layout(int res, int guard);
int paraboloid_face_edge(int res);
// Projector layout for the projector's frame: one face of round(res·aspect) × res owned texels.
FaceLayout projector_layout(const Projector& projector, int res, int guard);
// Edge S of the tetrahedral texture for cube edge n: the even S with S² closest to 6·n².
int tetra_atlas_size(int n);

// Face owning direction `dir` (non-zero) from the light. (Inline: once per lookup.)
inline int face_of(const FaceLayout& layout, const vec3& dir) {
  if (layout.kind == FaceLayoutKind::Cube) return cube_face_of(dir);
  if (layout.kind == FaceLayoutKind::Projector) return 0;
  if (layout.kind == FaceLayoutKind::DualParaboloid)
    return glm::dot(dir, layout.faces[0].forward) >= 0.0f ? 0 : 1;
  int best = 0;
  float best_dot = glm::dot(dir, kTetraNormals[0]);
  for (int i = 1; i < 4; ++i) {
    const float d = glm::dot(dir, kTetraNormals[i]);
    if (d > best_dot) {
      best_dot = d;
      best = i;
    }
  }
  return best;
}
// Continuous texel coordinates (x right, y down, centres at +0.5) of `dir` in `face`. Valid
// for directions in front of the face (dir·forward > 0; paraboloid: dir·forward > −|dir|).
inline vec2 face_texel_coords(const LightFace& f, const vec3& dir) {
  const float inv = f.paraboloid ? 1.0f / (glm::length(dir) + glm::dot(dir, f.forward))
                                 : 1.0f / glm::dot(dir, f.forward);
  const float u = glm::dot(dir, f.right) * inv, v = glm::dot(dir, f.up) * inv;
  return vec2((u - f.left) / (f.right_edge - f.left) * float(f.width),
              (f.top - v) / (f.top - f.bottom) * float(f.height));
}
// Image-plane coordinates (u, v) of continuous texel coordinates st.
inline vec2 face_plane_coords(const LightFace& f, vec2 st) {
  return vec2(f.left + st.x / float(f.width) * (f.right_edge - f.left),
              f.top - st.y / float(f.height) * (f.top - f.bottom));
}
// World-space unit direction through continuous texel coordinates (sx, sy).
vec3 face_texel_direction(const LightFace& face, float sx, float sy);
// World → clip matrix of a face (OpenGL clip space, light near/far planes).
mat4 face_view_proj(const LightFace& face, const PointLight& light);
// Plane units per texel along u (the face's texel size at unit distance on its axis).
inline float face_texel_plane_size(const LightFace& f) {
  return (f.right_edge - f.left) / float(f.width);
}

}  // namespace shadowlab
