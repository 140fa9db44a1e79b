#include "scenes/mesh_builders.h"

#include <cmath>
#include <vector>

#include "core/error.h"

namespace shadowlab {

// Adds an empty mesh with its own material and returns it.
int add_quad_mesh(Scene& scene, vec3 a, vec3 b, vec3 c, vec3 d, int material,
                  std::vector<vec2> uvs) {
  Mesh m;
  m.name = "quad" + std::to_string(scene.meshes.size());
  m.positions = {a, b, c, d};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.uvs = std::move(uvs);
  m.material = material;
  compute_vertex_normals(m);
  scene.meshes.push_back(std::move(m));
  return int(scene.meshes.size()) - 1;
}

mat4 box_transform(vec3 centre, vec3 size, float deg, vec3 axis) {
  mat4 m = glm::translate(mat4(1.0f), centre);
  m = glm::rotate(m, glm::radians(deg), axis);
  return glm::scale(m, size);
}

Mesh& new_mesh(Scene& scene, const std::string& name, vec3 albedo) {
  Material mat;
  mat.name = name;
  mat.albedo = albedo;
  scene.materials.push_back(mat);
  Mesh mesh;
  mesh.name = name;
  mesh.material = int(scene.materials.size()) - 1;
  scene.meshes.push_back(std::move(mesh));
  return scene.meshes.back();
}
namespace {

constexpr float kPi = 3.14159265358979323846f;

uint32_t add_vertex(Mesh& mesh, vec3 p, vec3 n) {
  mesh.positions.push_back(p);
  mesh.normals.push_back(n);
  return uint32_t(mesh.positions.size() - 1);
}

// Appends triangle (a, b, c), swapping b and c when needed so that it faces `outward`.
void add_oriented(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c, vec3 outward) {
  const vec3 n =
      glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
  if (glm::dot(n, outward) < 0.0f) std::swap(b, c);
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

}  // namespace

void add_grid_quad(Mesh& mesh, vec3 origin, vec3 edge_u, vec3 edge_v, int nu, int nv) {
  SL_CHECK(nu >= 1 && nv >= 1);
  const vec3 n = glm::normalize(glm::cross(edge_u, edge_v));
  const uint32_t base = uint32_t(mesh.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      add_vertex(mesh, origin + edge_u * (float(i) / float(nu)) + edge_v * (float(j) / float(nv)),
                 n);
  const uint32_t row = uint32_t(nu + 1);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const uint32_t a = base + uint32_t(j) * row + uint32_t(i);
      // (s,t), (s+1,t), (s+1,t+1) is counter-clockwise seen from cross(edge_u, edge_v).
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
    }
}

void add_box(Mesh& mesh, const mat4& model) {
  const glm::mat3 linear(model);
  SL_CHECK(glm::determinant(linear) > 0.0f);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  // Per face of the unit cube: outward normal and two in-face axes with cross(u, v) = normal.
  struct Face {
    vec3 n, u, v;
  };
  static const Face kFaces[6] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  for (const Face& f : kFaces) {
    const vec3 n = glm::normalize(normal_matrix * f.n);
    const vec3 corner = 0.5f * (f.n - f.u - f.v);  // model space, the face's (0, 0) corner
    const uint32_t base = uint32_t(mesh.positions.size());
    const vec3 local[4] = {corner, corner + f.u, corner + f.u + f.v, corner + f.v};
    for (const vec3& p : local) add_vertex(mesh, vec3(model * vec4(p, 1.0f)), n);
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
}

void add_uv_sphere(Mesh& mesh, vec3 centre, float radius, int segments, int rings) {
  SL_CHECK(segments >= 3 && rings >= 2 && radius > 0.0f);
  const uint32_t base = uint32_t(mesh.positions.size());
  const uint32_t row = uint32_t(segments + 1);  // the seam column is duplicated
  for (int r = 0; r <= rings; ++r) {
    const float theta = kPi * float(r) / float(rings);  // 0 at the north pole (+y)
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * kPi * float(s % segments) / float(segments);
      const vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi));
      add_vertex(mesh, centre + radius * d, d);
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = base + uint32_t(r) * row + uint32_t(s);
      const uint32_t b = a + 1, c = a + row, d = a + row + 1;
      const vec3 out = mesh.positions[a] + mesh.positions[d] - 2.0f * centre;
      if (r > 0) add_oriented(mesh, a, b, d, out);  // pole rows have one triangle
      if (r < rings - 1) add_oriented(mesh, a, d, c, out);
    }
}

void add_cylinder(Mesh& mesh, vec3 base, float radius, float height, int segments) {
  SL_CHECK(segments >= 3 && radius > 0.0f && height > 0.0f);
  const vec3 up(0.0f, 1.0f, 0.0f);
  const vec3 top = base + height * up;
  auto dir = [&](int s) {
    const float phi = 2.0f * kPi * float(s % segments) / float(segments);
    return vec3(std::cos(phi), 0.0f, std::sin(phi));
  };
  // Side: two rings with radial normals.
  const uint32_t side = uint32_t(mesh.positions.size());
  for (int s = 0; s <= segments; ++s) {
    add_vertex(mesh, base + radius * dir(s), dir(s));
    add_vertex(mesh, top + radius * dir(s), dir(s));
  }
  for (int s = 0; s < segments; ++s) {
    const uint32_t a = side + 2 * uint32_t(s);  // bottom s; a + 1 top s; a + 2 bottom s+1
    const vec3 out = dir(s) + dir(s + 1);
    add_oriented(mesh, a, a + 2, a + 3, out);
    add_oriented(mesh, a, a + 3, a + 1, out);
  }
  // Caps: a centre vertex and a ring with flat normals.
  for (int cap = 0; cap < 2; ++cap) {
    const vec3 c = cap == 0 ? base : top;
    const vec3 n = cap == 0 ? -up : up;
    const uint32_t centre = add_vertex(mesh, c, n);
    for (int s = 0; s <= segments; ++s) add_vertex(mesh, c + radius * dir(s), n);
    for (int s = 0; s < segments; ++s)
      add_oriented(mesh, centre, centre + 1 + uint32_t(s), centre + 2 + uint32_t(s), n);
  }
}

void add_torus(Mesh& mesh, vec3 centre, vec3 axis, float major, float minor, int major_segments,
               int minor_segments) {
  SL_CHECK(major_segments >= 3 && minor_segments >= 3);
  SL_CHECK(minor > 0.0f && major > minor && glm::length(axis) > 0.0f);
  const vec3 a = glm::normalize(axis);
  vec3 u = glm::cross(a, vec3(0.0f, 1.0f, 0.0f));
  if (glm::length(u) < 1e-3f) u = glm::cross(a, vec3(1.0f, 0.0f, 0.0f));
  u = glm::normalize(u);
  const vec3 v = glm::cross(a, u);
  // Angle tables once per call (not per vertex): the 1M-triangle scenes build in milliseconds.
  const size_t n_phi = static_cast<size_t>(major_segments);
  const size_t n_theta = static_cast<size_t>(minor_segments);
  std::vector<float> cos_phi(n_phi), sin_phi(n_phi), cos_theta(n_theta), sin_theta(n_theta);
  for (int i = 0; i < major_segments; ++i) {
    const float phi = 2.0f * kPi * float(i) / float(major_segments);
    cos_phi[size_t(i)] = std::cos(phi);
    sin_phi[size_t(i)] = std::sin(phi);
  }
  for (int j = 0; j < minor_segments; ++j) {
    const float theta = 2.0f * kPi * float(j) / float(minor_segments);
    cos_theta[size_t(j)] = std::cos(theta);
    sin_theta[size_t(j)] = std::sin(theta);
  }
  const uint32_t base = uint32_t(mesh.positions.size());
  const size_t vertices = size_t(major_segments) * size_t(minor_segments);
  mesh.positions.reserve(mesh.positions.size() + vertices);
  mesh.normals.reserve(mesh.normals.size() + vertices);
  mesh.indices.reserve(mesh.indices.size() + 6 * vertices);
  for (int i = 0; i < major_segments; ++i) {
    const vec3 radial = cos_phi[size_t(i)] * u + sin_phi[size_t(i)] * v;
    for (int j = 0; j < minor_segments; ++j) {
      const vec3 n = cos_theta[size_t(j)] * radial + sin_theta[size_t(j)] * a;
      add_vertex(mesh, centre + major * radial + minor * n, n);
    }
  }
  // Both rings wrap around: vertex (i, j) is base + i·minor_segments + j, indices taken modulo.
  // With (radial, tangent along φ, a) right-handed, (i, j) → (i+1, j) → (i+1, j+1) turns
  // counter-clockwise seen from outside the tube (normal n = cos θ·radial + sin θ·a).
  auto id = [&](int i, int j) {
    return base + uint32_t((i % major_segments) * minor_segments + (j % minor_segments));
  };
  for (int i = 0; i < major_segments; ++i)
    for (int j = 0; j < minor_segments; ++j) {
      const uint32_t p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1),
                     p01 = id(i, j + 1);
      mesh.indices.insert(mesh.indices.end(), {p00, p10, p11, p00, p11, p01});
    }
}

double signed_volume(const Mesh& mesh) {
  double v = 0.0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    v += glm::dot(a, glm::cross(b, c));
  }
  return v / 6.0;
}

}  // namespace shadowlab
