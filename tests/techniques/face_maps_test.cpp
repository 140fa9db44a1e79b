// The face-map techniques (tsm, cvsm, tvsm, cesm, tesm): analytic scenes, seams at face
// boundaries, agreement with Embree, texel indices, and bad parameters.
#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh_builders.h"
#include "techniques/face_map_technique.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

const char* const kFamily[] = {"tsm", "cvsm", "tvsm", "cesm", "tesm"};

double mismatch_rate(const ImageF& a, const ImageF& b) {
  size_t diff = 0;
  for (size_t i = 0; i < a.data.size(); ++i) diff += (a.data[i] > 0.5f) != (b.data[i] > 0.5f);
  return double(diff) / double(a.data.size());
}

// A plane with nothing between it and the light is lit by every technique and filter size,
// including PCF kernels and blurs that reach across face boundaries and map borders.
TEST(FaceMaps, UnoccludedPlaneIsLit) {
  const Scene scene = test::small_scene("plane", 96, 72);
  const GBuffer g = render_gbuffer(scene);
  for (const char* spec : {"tsm:res=64", "tsm:res=32,pcf=5", "tsm:res=256,pcf=3,normal=1",
                           "cvsm:res=64", "tvsm:res=64,blur=7", "cesm:res=64", "tesm:res=32,blur=9",
                           "cvsm:res=64,slope_moment=1,maxdepth_eps=0.05", "csm:res=64,normal=1"}) {
    const ShadowResult r = test::run(spec, scene, g);
    for (size_t i = 0; i < g.pixel_count(); ++i)
      ASSERT_GE(r.mask.data[i], 0.99f) << spec << " pixel " << i;
  }
}

// A closed box around an off-centre light: every wall point is lit. Receivers are placed on
// the walls in a dense Fibonacci set of directions (0.7° apart, about a texel of the res-256 maps),
// so every cube and tetrahedron face boundary and corner is crossed many times. Points within
// 0.4 m of the box's own (concave) edges are left out: there a filtered map legitimately
// darkens, because the adjacent wall is nearer than the receiver's plane (a blur of 7 texels
// plus the bilinear tap spans ±4.5 texels: ±4.5° on the tetrahedral axis at res 256, ≤ 0.3 m
// at the walls' ≤ 3.7 m).
struct BoxRoom {
  Scene scene;
  GBuffer g;
};

BoxRoom box_room() {
  BoxRoom b;
  Scene& s = b.scene;
  s.name = "box";
  s.materials.push_back(Material{});
  Mesh m;
  add_box(m, glm::scale(mat4(1.0f), vec3(4.0f)));
  s.meshes.push_back(m);
  s.light.position = vec3(0.3f, 0.2f, 0.1f);
  s.light.near = 0.05f;
  s.light.far = 10.0f;
  const int n = 90000;
  b.g.resize(n, 1);
  const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
  for (int i = 0; i < n; ++i) {
    const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n), r = std::sqrt(1.0f - y * y);
    const vec3 d(r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i)));
    float t = 1e30f;
    int axis = 0;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0f) continue;
      const float ta = ((d[a] > 0.0f ? 2.0f : -2.0f) - s.light.position[a]) / d[a];
      if (ta < t) t = ta, axis = a;
    }
    const vec3 p = s.light.position + t * d;
    int near_edges = 0;
    for (int a = 0; a < 3; ++a) near_edges += std::fabs(p[a]) > 1.6f;
    if (near_edges >= 2) continue;
    vec3 normal(0.0f);
    normal[axis] = d[axis] > 0.0f ? -1.0f : 1.0f;
    b.g.position[size_t(i)] = p;
    b.g.normal[size_t(i)] = b.g.geo_normal[size_t(i)] = normal;
    b.g.covered[size_t(i)] = 1;
  }
  return b;
}

TEST(FaceMaps, NoSeamsAcrossFaceBoundariesAndCorners) {
  const BoxRoom room = box_room();
  for (const char* spec : {"tsm:res=256", "tsm:res=256,pcf=5", "cvsm:res=256,blur=7",
                           "tvsm:res=256,blur=7", "cesm:res=256,blur=7", "tesm:res=256,blur=7",
                           "csm:res=256,pcf=5"}) {
    const ShadowResult r = test::run(spec, room.scene, room.g);
    float worst = 1.0f;
    for (size_t i = 0; i < room.g.pixel_count(); ++i)
      if (room.g.covered[i]) worst = std::min(worst, r.mask.data[i]);
    EXPECT_GE(worst, 0.99f) << spec;
  }
}

// The seam test can fail: the same blurred VSM without its guard band (the blur clamps at each
// face's edge and meets the neighbouring face's different depths) darkens boundary texels.
TEST(FaceMaps, WithoutGuardBandTheBlurLeavesSeams) {
  const BoxRoom room = box_room();
  FaceMapParams p = parse_face_map_params(parse_technique_spec("cvsm:res=256,blur=7", "t"), "t");
  FaceMap map;
  map.layout = cube_layout(p.res, 0);
  build_face_map(room.scene, p, std::vector<bool>(6, true), map);
  ImageF mask;
  lookup_face_map(room.scene, room.g, p, map, mask, nullptr);
  float worst = 1.0f;
  for (size_t i = 0; i < room.g.pixel_count(); ++i)
    if (room.g.covered[i]) worst = std::min(worst, mask.data[i]);
  EXPECT_LT(worst, 0.9f);
}

// Fine maps agree with one Embree ray per pixel almost everywhere (a 1024 map gives several
// texels per pixel of a 160×120 image: only shadow-edge pixels may differ), and a coarse map
// disagrees more.
TEST(FaceMaps, FineMapsMatchHardRayTracing) {
  Scene scene = test::small_scene("default", 160, 120);
  scene.light.radius = 0.0f;
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult rt = test::run("rt", scene, g);
  for (const char* name : kFamily) {
    const ShadowResult fine = test::run(std::string(name) + ":res=1024", scene, g);
    const ShadowResult coarse = test::run(std::string(name) + ":res=32", scene, g);
    EXPECT_LT(mismatch_rate(fine.mask, rt.mask), 0.02) << name;
    EXPECT_GT(mismatch_rate(coarse.mask, rt.mask), mismatch_rate(fine.mask, rt.mask)) << name;
    for (float v : fine.mask.data) ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << name;
  }
}

TEST(FaceMaps, TexelIndicesAreInRangeWhereExpected) {
  const Scene scene = test::small_scene("default", 80, 60);
  const GBuffer g = render_gbuffer(scene);
  for (const char* name : kFamily) {
    const ShadowResult r = test::run(std::string(name) + ":res=64", scene, g);
    const bool tetra = name[0] == 't';
    // Texels per face including the guard band; faces: 4 quadrants of S = 2·79 or 6 cube faces.
    const FaceMapParams p = parse_face_map_params(parse_technique_spec(std::string(name) + ":res=64", "t"), "t");
    const FaceLayout L = tetra ? tetra_layout(64, face_map_guard(p)) : cube_layout(64, face_map_guard(p));
    const uint32_t limit = uint32_t(L.faces.size() * L.faces[0].texel_count());
    EXPECT_EQ(r.faces_total, tetra ? 4 : 6);
    for (size_t i = 0; i < g.pixel_count(); ++i) {
      if (!(g.covered[i] && faces_light(g, i, scene.light.position))) {
        ASSERT_EQ(r.texels.data[i], kNoTexel) << name;
        continue;
      }
      ASSERT_LT(r.texels.data[i], limit) << name;
    }
  }
  EXPECT_EQ(tetra_layout(64, 2).atlas, 156);  // √6 · 64 = 156.8: 156² is closer to 24576 than 158²
}

TEST(FaceMaps, BadParametersAreRejected) {
  for (const char* bad : {"tsm:res=0", "tsm:pcf=2", "tsm:blur=3", "cvsm:pcf=3", "cvsm:blur=4",
                          "cvsm:bleed=1", "cvsm:min_variance=-1", "cesm:c=0", "cesm:c=701",
                          "tesm:min_variance=1", "tvsm:res=99999", "cvsm:slope_moment=2"}) {
    EXPECT_THROW(validate_technique(parse_technique_spec(bad, "--technique"), "--technique"),
                 InputError)
        << bad;
  }
}

}  // namespace
}  // namespace shadowlab
