#include "scenes/scene_library.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include "core/error.h"
#include "scenes/mesh_builders.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

// Möller–Trumbore ray/triangle intersection (both sides); the hit distance along a unit `dir`.
std::optional<float> intersect(vec3 orig, vec3 dir, vec3 a, vec3 b, vec3 c) {
  const vec3 e1 = b - a, e2 = c - a;
  const vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  if (std::fabs(det) < 1e-12f) return std::nullopt;
  const float inv = 1.0f / det;
  const vec3 s = orig - a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::nullopt;
  const vec3 q = glm::cross(s, e1);
  const float v = glm::dot(dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::nullopt;
  const float t = glm::dot(e2, q) * inv;
  if (t <= 0.0f) return std::nullopt;
  return t;
}

struct Hit {
  float t = INFINITY;
  int mesh = -1;
};

// Nearest hit of a ray over every triangle of the scene (brute force).
Hit trace(const Scene& s, vec3 orig, vec3 dir) {
  Hit h;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const Mesh& me = s.meshes[m];
    for (size_t i = 0; i < me.indices.size(); i += 3) {
      const auto t = intersect(orig, dir, me.positions[me.indices[i]],
                               me.positions[me.indices[i + 1]], me.positions[me.indices[i + 2]]);
      if (t && *t < h.t) h = {*t, int(m)};
    }
  }
  return h;
}

const Mesh* find_mesh(const Scene& s, const std::string& name) {
  for (const Mesh& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(SceneLibrary, DefaultSceneIsValidAndLightIsInsideTheRoom) {
  const Scene s = make_builtin_scene("default");
  EXPECT_NO_THROW(validate_scene(s, "default"));
  const vec3 L = s.light.position;
  EXPECT_TRUE(L.x > -5 && L.x < 5 && L.y > 0 && L.y < 4 && L.z > -5 && L.z < 5);
  EXPECT_GE(L.y, 2.5f);
  EXPECT_LE(L.y, 3.0f);
  EXPECT_FLOAT_EQ(s.light.radius, 0.03f);
  // far bounds the distance from the light to every vertex.
  for (const Mesh& m : s.meshes)
    for (const vec3& p : m.positions) ASSERT_LT(glm::length(p - L), s.light.far) << m.name;
  EXPECT_EQ(s.camera.width, 1024);
  EXPECT_EQ(s.camera.height, 768);
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 60.0f);
  for (const char* name : {"floor", "ceiling", "wall_north", "wall_south", "wall_west", "wall_east",
                           "box", "sphere", "pole", "table", "ramp"})
    EXPECT_NE(find_mesh(s, name), nullptr) << name;
  EXPECT_EQ(s.materials.size(), s.meshes.size()) << "one material per mesh";
  for (const Material& m : s.materials) EXPECT_EQ(m.alpha_texture, -1);
}

TEST(SceneLibrary, EveryCubeFaceOfTheLightSeesGeometry) {
  const Scene s = make_builtin_scene("default");
  const vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const vec3& d : axes) {
    const Hit h = trace(s, s.light.position, d);
    EXPECT_GE(h.mesh, 0) << "axis " << d.x << "," << d.y << "," << d.z;
    EXPECT_LT(h.t, s.light.far);
  }
}

TEST(SceneLibrary, OccludersCastShadowsOnTheFloorAndTheRamp) {
  // Shadow rays from points just below each occluder towards the light are blocked by it.
  const Scene s = make_builtin_scene("default");
  const vec3 L = s.light.position;
  struct Probe {
    vec3 floor_point;
    const char* occluder;
  };
  const Probe probes[] = {{{-2.9f, 0.0f, -1.5f}, "box"},    // behind the box (-x)
                          {{2.3f, 0.0f, 1.5f}, "sphere"},   // contact region of the sphere
                          {{2.4f, 0.0f, -2.6f}, "table"},   // under the table top
                          {{-1.33f, 0.0f, 0.78f}, "pole"},  // 0.6 m beyond the pole
                          {{-4.0f, 0.0f, 1.9f}, "ramp"}};   // behind/under the ramp
  for (const Probe& p : probes) {
    const vec3 dir = glm::normalize(L - p.floor_point);
    const Hit h = trace(s, p.floor_point + 1e-4f * vec3(0, 1, 0), dir);
    ASSERT_GE(h.mesh, 0) << p.occluder;
    EXPECT_EQ(s.meshes[size_t(h.mesh)].name, p.occluder);
    EXPECT_LT(h.t, glm::length(L - p.floor_point));
  }
}

TEST(SceneLibrary, DefaultSceneOrientationAndNormals) {
  const Scene s = make_builtin_scene("default");
  double room_volume = 0.0;
  for (const Mesh& m : s.meshes) {
    const bool room = m.name == "floor" || m.name == "ceiling" || m.name.rfind("wall_", 0) == 0;
    if (room)
      room_volume += signed_volume(m);
    else
      EXPECT_GT(signed_volume(m), 0.0) << m.name << " faces outward";
    // Vertex normals are unit and on the front side of every triangle using them. The room's
    // big planes are tessellated into 1.25 m cells (edges <= 1.25·√2 m); the pole's 3.2 m
    // slivers are meant (thin-triangle case).
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (size_t i = 0; i < m.indices.size(); i += 3) {
      const vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                 c = m.positions[m.indices[i + 2]];
      const vec3 g = glm::cross(b - a, c - a);
      for (int k = 0; k < 3; ++k) {
        const vec3 n = m.normals[m.indices[i + size_t(k)]];
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(n, g), 0.0f) << m.name << " triangle " << i / 3;
      }
      if (room) {
        EXPECT_LE(std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)}), 1.8f)
            << m.name;
      }
    }
  }
  // Seen from inside, the room's inward faces enclose -(10 · 4 · 10) m³.
  EXPECT_NEAR(room_volume, -400.0, 1e-3);
  // Room surfaces face the room centre.
  for (const char* name :
       {"floor", "ceiling", "wall_north", "wall_south", "wall_west", "wall_east"}) {
    const Mesh* m = find_mesh(s, name);
    ASSERT_NE(m, nullptr);
    EXPECT_GT(glm::dot(m->normals[0], vec3(0, 2, 0) - m->positions[0]), 0.0f) << name;
  }
}

TEST(SceneLibrary, RampTopIsAGrazingReceiver) {
  // Every vertex of the ramp's top face sees the light at a grazing angle: 0 < N·L < 0.2.
  const Scene s = make_builtin_scene("default");
  const Mesh* ramp = find_mesh(s, "ramp");
  ASSERT_NE(ramp, nullptr);
  int top_vertices = 0;
  for (size_t i = 0; i < ramp->positions.size(); ++i) {
    const vec3 n = ramp->normals[i];
    if (n.y < 0.7f) continue;  // not the top face
    ++top_vertices;
    const float ndotl = glm::dot(n, glm::normalize(s.light.position - ramp->positions[i]));
    EXPECT_GT(ndotl, 0.0f) << "vertex " << i;
    EXPECT_LT(ndotl, 0.2f) << "vertex " << i;
  }
  EXPECT_EQ(top_vertices, 4);
}

TEST(SceneLibrary, DefaultCameraSeesTheFloorAndSeveralOccluders) {
  const Scene s = make_builtin_scene("default");
  const mat4 inv = glm::inverse(camera_projection(s.camera) * camera_view(s.camera));
  std::vector<int> seen(s.meshes.size(), 0);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      const vec4 ndc(2.0f * (float(x) + 0.5f) / 32.0f - 1.0f,
                     1.0f - 2.0f * (float(y) + 0.5f) / 24.0f, 1.0f, 1.0f);
      const vec4 w = inv * ndc;
      const vec3 dir = glm::normalize(vec3(w) / w.w - s.camera.eye);
      const Hit h = trace(s, s.camera.eye, dir);
      ASSERT_GE(h.mesh, 0) << "the closed room covers every pixel";
      ++seen[size_t(h.mesh)];
    }
  for (const char* name : {"floor", "wall_north", "box", "sphere", "table", "ramp"}) {
    size_t i = 0;
    while (s.meshes[i].name != name) ++i;
    EXPECT_GT(seen[i], 0) << name << " is in view";
  }
}

TEST(SceneLibrary, PlaneSceneIsUnoccludedFloor) {
  const Scene s = make_builtin_scene("plane");
  EXPECT_NO_THROW(validate_scene(s, "plane"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.light.position, vec3(0, 2, 0));
  for (const vec3& p : s.meshes[0].positions) {
    EXPECT_EQ(p.y, 0.0f);
    EXPECT_LT(glm::length(p - s.light.position), s.light.far);
  }
  for (const vec3& n : s.meshes[0].normals) EXPECT_EQ(n, vec3(0, 1, 0));
  // The image centre looks straight down at the origin.
  const vec3 fwd = glm::normalize(s.camera.target - s.camera.eye);
  EXPECT_NEAR(fwd.y, -1.0f, 1e-6f);
}

TEST(SceneLibrary, UnknownNameIsAnInputError) {
  try {
    make_builtin_scene("cornell");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "--scene");
    EXPECT_NE(std::string(e.what()).find("unknown built-in scene 'cornell'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("known: default, plane"), std::string::npos);
  }
}

TEST(SceneLibrary, CameraSizeHelper) {
  Scene s = make_builtin_scene("plane");
  apply_camera_size(s, 160, 120);
  EXPECT_EQ(s.camera.width, 160);
  EXPECT_EQ(s.camera.height, 120);
  EXPECT_THROW(apply_camera_size(s, 0, 120), InputError);
  EXPECT_THROW(apply_camera_size(s, 100, kMaxImageSide + 1), InputError);
}

TEST(SceneLibrary, ObjSceneIsFramedFromItsBounds) {
  // A tetrahedron far from the origin: every vertex projects inside the image, and the light
  // reaches every vertex.
  const std::string path = test::binary_path("core/obj/framed.obj");
  std::ofstream(path) << "v 100 50 -20\nv 102 50 -20\nv 100 53 -20\nv 100 50 -17\n"
                         "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  Scene s = make_obj_scene(path);
  const mat4 vp = camera_projection(s.camera) * camera_view(s.camera);
  const Bounds b = scene_bounds(s);
  for (int i = 0; i < 8; ++i) {
    const vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                      (i & 4) ? b.hi.z : b.lo.z);
    const vec4 clip = vp * vec4(corner, 1.0f);
    ASSERT_GT(clip.w, 0.0f);
    EXPECT_LE(std::fabs(clip.x / clip.w), 1.0f) << "corner " << i;
    EXPECT_LE(std::fabs(clip.y / clip.w), 1.0f) << "corner " << i;
    EXPECT_LT(glm::length(corner - s.light.position), s.light.far);
    EXPECT_GT(glm::length(corner - s.light.position), s.light.near);
  }
  EXPECT_GT(s.light.position.y, b.hi.y) << "light above the model";
  // The documented framing (scene_library.h): fov_y 60°, the eye along (0, 1, 1) from the
  // bounds centre at d = 1.05·r / sin(30°), r half the bounds diagonal.
  const float r = 0.5f * glm::length(b.extent());
  EXPECT_EQ(s.camera.fov_y_deg, 60.0f);
  EXPECT_NEAR(glm::length(s.camera.eye - b.centre()), 1.05f * r / 0.5f, 1e-4f);
  EXPECT_NEAR(glm::dot(glm::normalize(s.camera.eye - b.centre()), glm::normalize(vec3(0, 1, 1))), 1.0f, 1e-6f);
  EXPECT_EQ(s.camera.target, b.centre());
  EXPECT_GT(s.light.radius, 0.0f);
  // The documented light: c + 1.5·r·normalize(1, 1.5, 0.5), radius 0.01·r.
  EXPECT_NEAR(glm::length(s.light.position - b.centre()), 1.5f * r, 1e-4f);
  EXPECT_NEAR(glm::dot(glm::normalize(s.light.position - b.centre()), glm::normalize(vec3(1, 1.5f, 0.5f))),
              1.0f, 1e-6f);
  EXPECT_NEAR(s.light.radius, 0.01f * r, 1e-6f);
  add_ground_plane(s);
  EXPECT_NO_THROW(validate_scene(s, path));
  ASSERT_EQ(s.meshes.back().name, "ground");
  // The ground: a flat square under the model (at its lowest y), centred below its bounds'
  // centre, twice the bounds' diagonal a side (2·√(2² + 3² + 3²) = 2·√22 m), facing up, and
  // every corner within the light's range.
  const Mesh& ground = s.meshes.back();
  const float side = 2.0f * std::sqrt(22.0f);
  vec3 lo(1e30f), hi(-1e30f);
  for (const vec3& p : ground.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_EQ(lo.y, 50.0f);
  EXPECT_EQ(hi.y, 50.0f);
  EXPECT_NEAR(hi.x - lo.x, side, 1e-4f);
  EXPECT_NEAR(hi.z - lo.z, side, 1e-4f);
  EXPECT_NEAR(0.5f * (lo.x + hi.x), 101.0f, 1e-4f);
  EXPECT_NEAR(0.5f * (lo.z + hi.z), -18.5f, 1e-4f);
  for (const vec3& n : ground.normals) ASSERT_EQ(n, vec3(0, 1, 0));
  for (const vec3& p : ground.positions) EXPECT_LT(glm::length(p - s.light.position), s.light.far);
  // A light far off to one side: the ground's farthest corner from it sets the range.
  for (const vec3 off : {vec3(30, 5, 2), vec3(-25, 4, 20), vec3(3, 6, -40), vec3(-20, 3, -20)}) {
    Scene t = make_obj_scene(path);
    t.light.position = b.centre() + off;
    t.light.far = 1.0f;
    add_ground_plane(t);
    float farthest = 0.0f;
    for (const vec3& p : t.meshes.back().positions) farthest = std::max(farthest, glm::length(p - t.light.position));
    EXPECT_GE(t.light.far, farthest) << off.x << "," << off.z;
    EXPECT_LE(t.light.far, 1.03f * farthest) << off.x << "," << off.z;
  }
}

// A model too large to frame automatically is named as such (it used to fail with a message
// about a light the user never set); a model whose triangles all have zero area is an error
// (it used to render "faces 0/6" and an all-white mask without a word).
TEST(SceneLibrary, ObjScenesThatCannotBeFramedOrShadowedAreErrors) {
  auto expect_error = [](const std::string& name, const std::string& text, const std::string& needle) {
    const std::string path = test::binary_path("core/obj/" + name);
    std::ofstream(path) << text;
    try {
      make_obj_scene(path);
      ADD_FAILURE() << name << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  expect_error("huge.obj", "v 0 0 0\nv 1e38 0 0\nv 0 1e38 0\nf 1 2 3\n", "too large to frame");
  expect_error("flat.obj", "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 1 1 1\nf 1 2 3\nf 1 2 4\n", "zero area");
  // A sliver of tiny but non-zero area is a model.
  const std::string ok = test::binary_path("core/obj/sliver.obj");
  std::ofstream(ok) << "v 0 0 0\nv 1 0 0\nv 0 1e-3 0\nf 1 2 3\n";
  EXPECT_NO_THROW(make_obj_scene(ok));
}

TEST(SceneLibrary, Room100kUsesTheCameraAndLightOfItsHeader) {
  std::vector<std::string> notes;
  const Scene s = make_obj_scene(test::assets_dir() + "/bench/room100k.obj", &notes);
  EXPECT_EQ(s.light.position, vec3(0, 4, 0));
  EXPECT_FLOAT_EQ(s.light.near, 0.05f);
  EXPECT_FLOAT_EQ(s.light.far, 40.0f);
  EXPECT_EQ(s.camera.eye, vec3(0.0f, 4.5f, 9.5f));
  EXPECT_EQ(s.camera.target, vec3(0, 3, 0));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 60.0f);
  EXPECT_EQ(s.camera.width, 1024);
  EXPECT_EQ(s.camera.height, 768);
}

}  // namespace
}  // namespace shadowlab
