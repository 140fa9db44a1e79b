#pragma once
// Procedural geometry for built-in scenes and tests. Every builder appends positions, per-vertex
// normals and indices to a Mesh (no uvs), with triangles counter-clockwise seen from the front
// side: the side the normal points to (outward for solids). Units: metres.
#include "core/math.h"
#include "core/scene.h"

namespace shadowlab {

// Appends an empty mesh with its own material (albedo, opaque) to the scene and returns it.
Mesh& new_mesh(Scene& scene, const std::string& name, vec3 albedo);

// Appends the quad a, b, c, d (counter-clockwise seen from its front) as one mesh named
// "quad<index>" with the given material and per-corner uvs (or none), area-weighted normals;
// returns its mesh index. (For tests and small hand-built scenes.)
int add_quad_mesh(Scene& scene, vec3 a, vec3 b, vec3 c, vec3 d, int material = 0,
                  std::vector<vec2> uvs = {});

// Planar rectangle origin + s·edge_u + t·edge_v, s, t in [0, 1], split into nu × nv quads
// (2 triangles each). Front side and flat normal: normalize(cross(edge_u, edge_v)).
void add_grid_quad(Mesh& mesh, vec3 origin, vec3 edge_u, vec3 edge_v, int nu, int nv);

// The `model` for add_box of a box of `size` (m) centred at `centre`, turned by `deg` degrees
// about `axis` through its centre.
mat4 box_transform(vec3 centre, vec3 size, float deg = 0.0f, vec3 axis = vec3(0, 1, 0));

// Box = the unit cube [-0.5, 0.5]³ mapped by `model` (scale, rotate, translate; determinant
// > 0). 24 vertices (flat normals per face), 12 triangles, outward.
void add_box(Mesh& mesh, const mat4& model);

// UV sphere around `centre`: `segments` around the y axis, `rings` from pole to pole; smooth
// normals. Triangles: 2·segments·(rings − 1).
void add_uv_sphere(Mesh& mesh, vec3 centre, float radius, int segments, int rings);

// Closed cylinder along +y from `base` (centre of the bottom cap) to base + (0, height, 0):
// smooth side normals, flat caps. Triangles: 4·segments.
void add_cylinder(Mesh& mesh, vec3 base, float radius, float height, int segments);

// Torus around `centre` with symmetry axis `axis` (any length > 0): tube of radius `minor`
// swept along a circle of radius `major` (> minor) in the plane normal to the axis; smooth
// normals, triangles facing outward. Vertex (i, j), i < major_segments, j < minor_segments:
//   p = centre + (major + minor·cos θj)·(cos φi·u + sin φi·v) + minor·sin θj·a,
// φi = 2π·i/major_segments, θj = 2π·j/minor_segments, a = normalize(axis),
// u = normalize(cross(a, +y)) (cross(a, +x) when a is within ~0.06° of ±y), v = cross(a, u).
// Triangles: 2·major_segments·minor_segments.
void add_torus(Mesh& mesh, vec3 centre, vec3 axis, float major, float minor, int major_segments,
               int minor_segments);

// Signed volume of a mesh (m³): positive when a closed mesh's triangles face outward,
// negative when they face inward (a room seen from inside).
double signed_volume(const Mesh& mesh);

}  // namespace shadowlab
