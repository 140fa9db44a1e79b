#include "gl_depth_cube.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "techniques/pipeline/light_faces.h"

namespace shadowlab {
namespace {

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * vec4(position, 1.0); }
)";

// Depth only: the fragment stage writes nothing but the fixed-function depth.
const char* kFragmentShader = R"(#version 450 core
void main() {}
)";

GLuint compile_stage(GLenum stage, const char* source) {
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = GL_FALSE;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("GL: shader does not compile: ") + log);
  }
  return s;
}

GLuint link_program() {
  const GLuint vs = compile_stage(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile_stage(GL_FRAGMENT_SHADER, kFragmentShader);
  const GLuint p = glCreateProgram();
  glAttachShader(p, vs);
  glAttachShader(p, fs);
  glLinkProgram(p);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("GL: the depth program does not link");
  return p;
}

}  // namespace

GlDepthCube make_gl_depth_cube(const Scene& scene, int res) {
  GlDepthCube c;
  c.res = res;
  c.near = scene.light.near;
  c.far = scene.light.far;

  // Every mesh in one vertex buffer and one index buffer (indices rebased per mesh).
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    const uint32_t base = static_cast<uint32_t>(positions.size() / 3);
    for (const vec3& p : m.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    for (const uint32_t i : m.indices) indices.push_back(base + i);
  }
  c.index_count = static_cast<int>(indices.size());

  c.program = link_program();
  c.view_projection_uniform = glGetUniformLocation(c.program, "view_projection");
  glGenVertexArrays(1, &c.vao);
  glBindVertexArray(c.vao);
  glGenBuffers(1, &c.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, c.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(float)), positions.data(),
               GL_STATIC_DRAW);
  glGenBuffers(1, &c.ibo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, c.ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)),
               indices.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);

  glGenTextures(1, &c.texture);
  glBindTexture(GL_TEXTURE_CUBE_MAP, c.texture);
  glTexStorage2D(GL_TEXTURE_CUBE_MAP, 1, GL_DEPTH_COMPONENT32F, res, res);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  // shadowlab's own face matrices: both render the same images (GL's rows bottom first).
  const FaceLayout layout = cube_layout(res, 0);
  glGenFramebuffers(6, c.framebuffers);
  for (int f = 0; f < 6; ++f) {
    const mat4 vp = face_view_proj(layout.faces[size_t(f)], scene.light);
    const float* m = glm::value_ptr(vp);
    for (int k = 0; k < 16; ++k) c.view_projection[f][k] = m[k];
    glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffers[f]);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                           GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), c.texture, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("GL: the depth framebuffer of face " + std::to_string(f) +
                               " is incomplete");
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL: setting up the cube failed");
  return c;
}

void render_gl_depth_cube(const GlDepthCube& c) {
  glUseProgram(c.program);
  glBindVertexArray(c.vao);
  for (int f = 0; f < 6; ++f) {
    glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffers[f]);
    glViewport(0, 0, c.res, c.res);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUniformMatrix4fv(c.view_projection_uniform, 1, GL_FALSE, c.view_projection[f]);
    glDrawElements(GL_TRIANGLES, c.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glFinish();
}

std::vector<std::vector<float>> gl_radial_distances(const GlDepthCube& c) {
  const size_t n_texels = size_t(c.res) * size_t(c.res);
  std::vector<float> depth(n_texels);
  std::vector<std::vector<float>> out(6, std::vector<float>(n_texels));
  glBindTexture(GL_TEXTURE_CUBE_MAP, c.texture);
  const double n = c.near, f = c.far;
  for (int face = 0; face < 6; ++face) {
    glGetTexImage(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                  depth.data());
    for (int y = 0; y < c.res; ++y)  // GL row y (from the bottom) is row res − 1 − y here
      for (int x = 0; x < c.res; ++x) {
        const double d = depth[size_t(y) * size_t(c.res) + size_t(x)];
        float& r = out[size_t(face)][size_t(c.res - 1 - y) * size_t(c.res) + size_t(x)];
        if (d >= 1.0) {  // cleared: no surface in this texel
          r = INFINITY;
          continue;
        }
        // Window depth d -> NDC z = 2d − 1 -> distance along the face's forward axis (the
        // inverse of the perspective depth row), then along the texel-centre ray, whose
        // direction is (u, v, 1) in face coordinates, u, v in [−1, 1] (90°).
        const double z_ndc = 2.0 * d - 1.0;
        const double along = 2.0 * f * n / (f + n - z_ndc * (f - n));
        const double u = 2.0 * (x + 0.5) / c.res - 1.0, v = 2.0 * (y + 0.5) / c.res - 1.0;
        r = float(along * std::sqrt(1.0 + u * u + v * v));
      }
  }
  return out;
}

void destroy_gl_depth_cube(GlDepthCube& c) {
  glDeleteFramebuffers(6, c.framebuffers);
  glDeleteTextures(1, &c.texture);
  glDeleteBuffers(1, &c.ibo);
  glDeleteBuffers(1, &c.vbo);
  glDeleteVertexArrays(1, &c.vao);
  glDeleteProgram(c.program);
  c = GlDepthCube{};
}

}  // namespace shadowlab
