// The rasterizer against Embree on big scenes, pixel by pixel and texel by texel:
//  - the camera pass (render_gbuffer) against primary rays (primary_visibility) for the
//    Stanford bunny and the 1M-triangle room (the default scene is in raster_vs_embree_test);
//  - every cube shadow-map face of the light (6 faces, 90°, the light's near plane) of the
//    default scene, room1m and the bunny on a ground quad, rasterized with a shader that records
//    the triangle per texel, against face_rays through the same texel centres.
// Criterion: the same primitive at >= 99.5 % of the covered pixels/texels, and where it
// is the same, the view depth (1/inv_w, or GBuffer depth) within 1e-4 relative at >= 99.5 % of
// them; covered-vs-hit disagreements (silhouettes) at <= 0.5 % of all pixels/texels. Where they
// differ legitimately: pixel centres within float rounding of a shared edge (the rasterizer's
// top-left rule on vertices snapped to 1/256 pixel vs Embree's float test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "scenes/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "raster/pipeline.h"
#include "raytrace/embree_scene.h"
#include "raytrace/face_rays.h"
#include "raytrace/visibility.h"
#include "test_paths.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// A scene with its Embree twin, built once per test binary (room1m's BVH is the costly part).
struct Case {
  Scene scene;
  std::unique_ptr<EmbreeScene> rt;
};

std::string bunny_path() { return test::assets_dir() + "/bunny/stanford-bunny.obj"; }

// "default", "room1m", "bunny" (as make_obj_scene frames it) or "bunny+ground" (the same on the
// ground quad of add_ground_plane, so the light's lower faces see a receiver).
const Case& get_case(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Case>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<Case>();
    if (name == "bunny" || name == "bunny+ground") {
      std::vector<std::string> notes;
      slot->scene = make_obj_scene(bunny_path(), &notes);
      if (name == "bunny+ground") add_ground_plane(slot->scene);
    } else {
      slot->scene = make_builtin_scene(name);
    }
    slot->rt = std::make_unique<EmbreeScene>(slot->scene);
  }
  return *slot;
}

struct Agreement {
  size_t total = 0;          // pixels or texels
  size_t covered = 0;        // covered by the rasterizer
  size_t same = 0;           // ... and the same (mesh, primitive) as Embree
  size_t depth_ok = 0;       // ... and the depth within 1e-4 relative
  size_t coverage_diff = 0;  // covered by exactly one of the two
  double max_depth_err = 0;  // largest relative depth error where the primitive is the same

  void add(uint32_t mesh, uint32_t prim, float depth, const PrimaryHits& hits, size_t i) {
    ++total;
    const bool hit = hits.mesh_id[i] != kNoPrimitive;
    const bool cov = mesh != kNoPrimitive;
    if (hit != cov) ++coverage_diff;
    if (!cov) return;
    ++covered;
    if (mesh != hits.mesh_id[i] || prim != hits.prim_id[i]) return;
    ++same;
    const double err = std::fabs(double(depth) - double(hits.depth[i])) / double(hits.depth[i]);
    max_depth_err = test::worst_of(max_depth_err, err);
    if (err <= 1e-4) ++depth_ok;
  }
};

std::ostream& operator<<(std::ostream& os, const Agreement& a) {
  return os << a.same << " of " << a.covered << " covered with the same primitive, " << a.depth_ok
            << " with depth within 1e-4 (max err " << a.max_depth_err << "), " << a.coverage_diff
            << " of " << a.total << " covered by one side only";
}

// The criterion; a face or image with under 2000 covered texels (a glimpse of a
// silhouette) may instead differ at up to 10 of them, where a percentage means nothing.
void expect_agreement(const Agreement& a, const std::string& what) {
  const double slack = a.covered < 2000 ? 10.0 : 0.0;
  EXPECT_GE(double(a.same) + slack, 0.995 * double(a.covered)) << what << ": " << a;
  EXPECT_GE(double(a.depth_ok) + slack, 0.995 * double(a.same)) << what << ": " << a;
  EXPECT_LE(double(a.coverage_diff), 0.005 * double(a.total) + slack) << what << ": " << a;
}

void expect_camera_pass_agrees(const std::string& name, int width, int height) {
  const Case& c = get_case(name);
  Scene scene = c.scene;  // geometry copied; only the image size changes
  scene.camera.width = width;
  scene.camera.height = height;
  const GBuffer g = render_gbuffer(scene);
  const PrimaryHits hits = primary_visibility(*c.rt, scene.camera);
  Agreement a;
  for (size_t i = 0; i < g.pixel_count(); ++i)
    a.add(g.covered[i] ? g.mesh_id[i] : kNoPrimitive, g.prim_id[i], g.depth[i], hits, i);
  expect_agreement(a, name + " camera pass");
  EXPECT_GT(a.covered, g.pixel_count() / 20) << "the view must show the scene";
  std::cout << "[ info     ] " << name << " camera " << width << "x" << height << ": " << a << "\n";
}

TEST(RasterVsEmbreeScenes, BunnyCameraPass) {
  expect_camera_pass_agrees("bunny", 512, 384);
}

TEST(RasterVsEmbreeScenes, Room1mCameraPass) { expect_camera_pass_agrees("room1m", 512, 384); }

// Records, per texel, the triangle of the last kept fragment (the visible one) — through the
// rasterizer's general path (this shader has side effects, so no fast path may skip it).
struct TriangleIdShader {
  static constexpr bool kNeedsAttributes = false;
  int width;
  uint32_t* ids;
  bool operator()(const Fragment& f) {
    ids[size_t(f.y) * size_t(width) + size_t(f.x)] = f.triangle;
    return true;
  }
};

// Cube-face views of a light (same axes as techniques/pipeline/cube_faces.cpp: +X −X +Y −Y +Z −Z).
mat4 light_face_view(vec3 light, int face) {
  static const vec3 kForward[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                   {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  static const vec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                              {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  return glm::lookAtRH(light, light + kForward[face], kUp[face]);
}

void expect_faces_agree(const std::string& name, int res) {
  const Case& c = get_case(name);
  const Scene& scene = c.scene;
  const std::vector<MeshView> meshes = scene_mesh_views(scene);
  const std::vector<uint32_t> first = scene_first_triangles(scene);
  const mat4 proj =
      glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, scene.light.near, scene.light.far);
  size_t faces_with_geometry = 0;
  for (int face = 0; face < 6; ++face) {
    const mat4 view = light_face_view(scene.light.position, face);
    std::vector<uint32_t> ids(size_t(res) * res, kNoPrimitive);
    TriangleIdShader shader{res, ids.data()};
    DepthTarget depth;
    rasterize(meshes, proj * view, CullMode::None, res, res, depth, shader);
    // The shadow maps themselves come from the depth-only fast path: same bytes required.
    DepthTarget fast;
    DepthOnlyShader depth_only;
    rasterize(meshes, proj * view, CullMode::None, res, res, fast, depth_only);
    EXPECT_EQ(0, std::memcmp(fast.inv_w.data(), depth.inv_w.data(), depth.inv_w.size() * 4))
        << name << " face " << face << ": depth-only path differs from the general path";

    const PrimaryHits hits = face_rays(*c.rt, view, proj, res);
    Agreement a;
    for (size_t i = 0; i < ids.size(); ++i) {
      uint32_t mesh = kNoPrimitive, prim = kNoPrimitive;
      if (ids[i] != kNoPrimitive) {
        mesh = uint32_t(std::upper_bound(first.begin(), first.end(), ids[i]) - first.begin()) - 1;
        prim = ids[i] - first[mesh];
      }
      a.add(mesh, prim, depth.inv_w[i] > 0.0f ? 1.0f / depth.inv_w[i] : INFINITY, hits, i);
    }
    faces_with_geometry += a.covered > 0;
    expect_agreement(a, name + " face " + std::to_string(face));
    std::cout << "[ info     ] " << name << " face " << face << " " << res << "²: " << a << "\n";
  }
  EXPECT_GT(faces_with_geometry, 0u);
}

TEST(RasterVsEmbreeScenes, DefaultSceneShadowFaces) { expect_faces_agree("default", 384); }

TEST(RasterVsEmbreeScenes, Room1mShadowFaces) { expect_faces_agree("room1m", 512); }

TEST(RasterVsEmbreeScenes, BunnyShadowFaces) {
  expect_faces_agree("bunny+ground", 512);
}

}  // namespace
}  // namespace shadowlab
