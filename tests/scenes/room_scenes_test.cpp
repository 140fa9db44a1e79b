// The built-in benchmark rooms "room100k" and "room1m" and the torus builder they use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scenes/mesh_builders.h"
#include "scenes/scene_library.h"
#include "test_paths.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

Bounds vertex_bounds(const Mesh& m) {
  Bounds b;
  for (const vec3& p : m.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

// Largest distance from a vertex of one mesh to the nearest vertex of the other, both ways.
double vertex_set_distance(const Mesh& a, const Mesh& b) {
  double worst = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    const Mesh& from = pass == 0 ? a : b;
    const Mesh& to = pass == 0 ? b : a;
    for (const vec3& p : from.positions) {
      float best = INFINITY;
      for (const vec3& q : to.positions) best = std::min(best, glm::dot(p - q, p - q));
      worst = test::worst_of(worst, std::sqrt(double(best)));
    }
  }
  return worst;
}

TEST(MeshBuilders, TorusIsClosedOutwardAndOnItsSurface) {
  // Tube radius 0.3 around a circle of radius 1.2 about the axis (1, 2, 0.5), centre (3, −1, 2):
  // every vertex lies at distance 0.3 from the circle, normals are unit and point away from
  // it, the triangles face outward (signed volume > 0) and the volume approaches the exact
  // 2π²Rr² from below (inscribed polygons: factor sin(2π/M)/(2π/M) · sin(2π/m)/(2π/m)).
  const vec3 c(3.0f, -1.0f, 2.0f), axis(1.0f, 2.0f, 0.5f);
  const float R = 1.2f, r = 0.3f;
  const int M = 48, m = 24;
  Mesh mesh;
  add_torus(mesh, c, axis, R, r, M, m);
  EXPECT_EQ(mesh.triangle_count(), size_t(2 * M * m));
  EXPECT_EQ(mesh.positions.size(), size_t(M * m));
  const dvec3 a = glm::normalize(dvec3(axis));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const dvec3 q = dvec3(mesh.positions[i]) - dvec3(c);
    const double h = glm::dot(q, a);
    const dvec3 radial = q - h * a;
    const dvec3 on_circle = double(R) * glm::normalize(radial);
    const dvec3 from_circle = q - on_circle;
    ASSERT_NEAR(glm::length(from_circle), r, 1e-5) << "vertex " << i;
    ASSERT_NEAR(glm::length(dvec3(mesh.normals[i])), 1.0, 1e-5);
    ASSERT_GT(glm::dot(dvec3(mesh.normals[i]), from_circle), 0.99 * r);
  }
  const double exact = 2.0 * kPi * kPi * R * r * r;
  const double sinc = std::sin(2 * kPi / M) / (2 * kPi / M) * std::sin(2 * kPi / m) / (2 * kPi / m);
  EXPECT_NEAR(signed_volume(mesh), exact * sinc, 2e-3 * exact);
  // An axis along ±y (the fallback basis) gives the same shape.
  Mesh flat;
  add_torus(flat, vec3(0.0f), vec3(0.0f, -1.0f, 0.0f), R, r, M, m);
  EXPECT_NEAR(signed_volume(flat), exact * sinc, 2e-3 * exact);
  const Bounds b = vertex_bounds(flat);
  EXPECT_NEAR(b.hi.y, r, 1e-6);
  EXPECT_NEAR(b.lo.y, -r, 1e-6);
}

TEST(RoomScenes, NamesAreListed) {
  const std::vector<std::string> names = builtin_scene_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "room100k"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "room1m"), names.end());
}

// Layout shared by both rooms: mesh 0 "room" (12 triangles: ground, ceiling, 4 walls), then
// object0..object63 alternating spheres and tori, every object inside the 20 × 8 × 20 m room,
// the OBJ's light and camera.
void expect_room_layout(const Scene& s, size_t sphere_tris, size_t torus_tris) {
  ASSERT_EQ(s.meshes.size(), 65u);
  EXPECT_EQ(s.meshes[0].name, "room");
  EXPECT_EQ(s.meshes[0].triangle_count(), 12u);
  const Bounds room = vertex_bounds(s.meshes[0]);
  EXPECT_EQ(room.lo, vec3(-30, 0, -30));
  EXPECT_EQ(room.hi, vec3(30, 8, 30));
  EXPECT_NEAR(signed_volume(s.meshes[0]), -20.0 * 20.0 * 8.0, 1e-2)
      << "the room's five quads face inward; the ground (at y = 0) adds no volume";
  for (int i = 0; i < 64; ++i) {
    const Mesh& m = s.meshes[size_t(i) + 1];
    EXPECT_EQ(m.name, "object" + std::to_string(i));
    EXPECT_EQ(m.triangle_count(), i % 2 == 0 ? sphere_tris : torus_tris) << m.name;
    EXPECT_GT(signed_volume(m), 0.0) << m.name << " faces outward";
    const Bounds b = vertex_bounds(m);
    EXPECT_GE(b.lo.y, -1e-4f) << m.name;
    EXPECT_LE(b.hi.y, 8.0f) << m.name;
    EXPECT_GE(std::min(b.lo.x, b.lo.z), -10.0f) << m.name;
    EXPECT_LE(std::max(b.hi.x, b.hi.z), 10.0f) << m.name;
  }
  EXPECT_EQ(s.light.position, vec3(0, 4, 0));
  EXPECT_EQ(s.light.radius, 0.0f);
  EXPECT_FLOAT_EQ(s.light.near, 0.05f);
  EXPECT_FLOAT_EQ(s.light.far, 40.0f);
  EXPECT_EQ(s.camera.eye, vec3(0.0f, 4.5f, 9.5f));
  EXPECT_EQ(s.camera.target, vec3(0, 3, 0));
  EXPECT_EQ(s.camera.up, vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 60.0f);
  EXPECT_EQ(s.camera.width, 1024);
  EXPECT_EQ(s.camera.height, 768);
}

TEST(RoomScenes, Room100kHasTheObjTessellation) {
  const Scene s = make_builtin_scene("room100k");
  EXPECT_EQ(s.triangle_count(), 99852u);  // as bench/room100k.obj
  expect_room_layout(s, 1520, 1600);
}

TEST(RoomScenes, Room1mIsTenTimesFiner) {
  const Scene s = make_builtin_scene("room1m");
  EXPECT_EQ(s.triangle_count(), 12u + 32u * 15360u + 32u * 15872u);  // 999,436
  expect_room_layout(s, 15360, 15872);
}

TEST(RoomScenes, MatchTheObjGroupByGroup) {
  // Both built-ins against the OBJ they replicate: the same meshes in the same order, the OBJ's
  // camera and light, and each object's bounds: room100k's to the OBJ's 6 printed digits
  // (0.2 mm), room1m's within the OBJ's coarser tessellation's sag (its polygons are inscribed:
  // a torus tube of 20 segments, r <= 0.385 m, sags 0.385·(1 − cos(π/20)) = 4.7 mm, its
  // 40-segment ring (R + r <= 1.19 m) 3.7 mm more; spheres (r <= 1.19 m, 40 × 20) 3.7 mm).
  // room100k's vertices are the OBJ's, up to its printed digits: every vertex of one mesh lies
  // within 0.1 mm of a vertex of the other (both ways).
  const std::string obj = test::assets_dir() + "/bench/room100k.obj";
  std::vector<std::string> notes;
  const Scene ref = make_obj_scene(obj, &notes);
  ASSERT_EQ(ref.meshes.size(), 65u);
  for (const char* name : {"room100k", "room1m"}) {
    const Scene s = make_builtin_scene(name);
    ASSERT_EQ(s.meshes.size(), ref.meshes.size()) << name;
    const float tol = std::string(name) == "room100k" ? 2e-4f : 9e-3f;
    for (size_t m = 0; m < ref.meshes.size(); ++m) {
      EXPECT_EQ(s.meshes[m].name, ref.meshes[m].name) << name;
      if (std::string(name) == "room100k") {
        EXPECT_EQ(s.meshes[m].triangle_count(), ref.meshes[m].triangle_count())
            << ref.meshes[m].name;
        EXPECT_LE(vertex_set_distance(s.meshes[m], ref.meshes[m]), 1e-4) << ref.meshes[m].name;
      }
      const Bounds a = vertex_bounds(s.meshes[m]), b = vertex_bounds(ref.meshes[m]);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a.lo[k], b.lo[k], tol) << name << " " << ref.meshes[m].name << " axis " << k;
        EXPECT_NEAR(a.hi[k], b.hi[k], tol) << name << " " << ref.meshes[m].name << " axis " << k;
      }
    }
    EXPECT_EQ(s.light.position, ref.light.position);
    EXPECT_EQ(s.light.radius, ref.light.radius);
    EXPECT_EQ(s.light.near, ref.light.near);
    EXPECT_EQ(s.light.far, ref.light.far);
    EXPECT_EQ(s.camera.eye, ref.camera.eye);
    EXPECT_EQ(s.camera.target, ref.camera.target);
    EXPECT_EQ(s.camera.up, ref.camera.up);
    EXPECT_EQ(s.camera.fov_y_deg, ref.camera.fov_y_deg);
    EXPECT_EQ(s.camera.near, ref.camera.near);
    EXPECT_EQ(s.camera.far, ref.camera.far);
    EXPECT_EQ(s.camera.width, ref.camera.width);
    EXPECT_EQ(s.camera.height, ref.camera.height);
  }
}

}  // namespace
}  // namespace shadowlab
