#pragma once
// The depth-only point-light cube shadow map in OpenGL: the scene's triangles in one vertex and
// one index buffer, six faces of res² texels (a 32-bit float depth cube map, one framebuffer per
// face, no colour), an empty fragment shader, no face culling. One render is, per face: bind
// its framebuffer, set the viewport, clear depth, set the face's view-projection, draw every
// triangle; then glFinish, so the time covers the rasterization and not only its submission.
// The faces are the light's cube faces of techniques/pipeline/light_faces.h with shadowlab's own
// world-to-clip matrices (face_view_proj), between the light's near and far.
#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace shadowlab {

struct GlDepthCube {
  int res = 0;
  float near = 0.0f, far = 0.0f;
  uint32_t program = 0, vao = 0, vbo = 0, ibo = 0, texture = 0;
  uint32_t framebuffers[6] = {};
  int index_count = 0;
  int view_projection_uniform = -1;
  float view_projection[6][16] = {};  // column-major, per face
};

// Uploads the scene and allocates the cube; needs a current OpenGL 4.5 core context.
// std::runtime_error when a shader, a buffer or a framebuffer cannot be made.
GlDepthCube make_gl_depth_cube(const Scene& scene, int res);

// Renders the six faces and waits for them (glFinish).
void render_gl_depth_cube(const GlDepthCube& cube);

// Per face, res² radial distances from the light in metres (+inf where no surface was drawn),
// recovered from the stored depth at each texel centre, rows top (v = +1) first as in
// techniques/pipeline/light_faces.h: the images to check against shadowlab's.
std::vector<std::vector<float>> gl_radial_distances(const GlDepthCube& cube);

void destroy_gl_depth_cube(GlDepthCube& cube);

}  // namespace shadowlab
