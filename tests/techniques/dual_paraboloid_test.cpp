// The dual-paraboloid layout (techniques/pipeline/light_faces.h, raster/paraboloid.h): its map and its
// inverse, render and lookup agreeing on where a direction lands, and its shadows against
// Embree's, with the linear-interpolation error falling as tess splits long edges.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "core/gbuffer.h"
#include "scenes/mesh_builders.h"
#include "raster/paraboloid.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/pipeline/paraboloid_tess.h"
#include "techniques/registry/technique.h"
#include "test_scenes.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

using test::mismatch_rate;

// Every direction lands in the face of its hemisphere (the equator in face 0), at texel
// coordinates whose direction is the same one (1e-4 rad, float), and the rasterizer's clip
// coordinates put it at those texel coordinates (1e-3 texel; measured 6.8e-5): render and lookup
// agree.
TEST(DualParaboloid, MapInverseAndRenderAgree) {
  const FaceLayout L = dual_paraboloid_layout(256, 3);
  ASSERT_EQ(L.faces.size(), 2u);
  EXPECT_EQ(L.faces[0].width, paraboloid_face_edge(256) + 6);
  EXPECT_EQ(paraboloid_face_edge(256), 443);  // round(√3 · 256)
  EXPECT_EQ(face_of(L, vec3(1.0f, 0.0f, 0.0f)), 0);
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0.0f, 1.0f);
  const vec3 light(0.3f, 1.0f, -0.2f);
  double worst_dir = 0.0, worst_texel = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const vec3 d = glm::normalize(vec3(g(rng), g(rng), g(rng)));
    const int f = face_of(L, d);
    EXPECT_EQ(f, d.y <= 0.0f ? 0 : 1);
    const LightFace& face = L.faces[size_t(f)];
    const vec2 st = face_texel_coords(face, d);
    ASSERT_TRUE(st.x >= 3.0f && st.x <= float(face.width) - 3.0f) << st.x;  // inside the disk
    const vec3 back = face_texel_direction(face, st.x, st.y);
    worst_dir = test::worst_of(worst_dir, double(glm::length(back - d)));
    ParaboloidProjection pp;
    pp.centre = light;
    pp.right = face.right;
    pp.up = face.up;
    pp.forward = face.forward;
    pp.left = face.left;
    pp.right_edge = face.right_edge;
    pp.bottom = face.bottom;
    pp.top = face.top;
    const vec4 c = paraboloid_clip(pp, light + 2.5f * d);
    // NDC → texel coordinates as the rasterizer maps them (x right, y down).
    const vec2 from_clip((c.x / c.w * 0.5f + 0.5f) * float(face.width),
                         (0.5f - c.y / c.w * 0.5f) * float(face.height));
    worst_texel = test::worst_of(worst_texel, double(glm::length(from_clip - st)));
    EXPECT_NEAR(c.w, 2.5f, 1e-5f);
    EXPECT_GE(c.z, -c.w);  // kept by the near-plane clip
  }
  RecordProperty("worst_direction", std::to_string(worst_dir));
  RecordProperty("worst_texel", std::to_string(worst_texel));
  EXPECT_LT(worst_dir, 1e-4);
  EXPECT_LT(worst_texel, 1e-3);
}

// Against one Embree ray per pixel (hard light, res 1024): DPSM's straight image edges make it
// disagree more than the cube; splitting edges longer than 16 texels (tess=16) brings it down, and
// res 32 disagrees more still. Measured (19,200 pixels): dsm 0.29 %, tess=16 0.089 %,
// res 32 2.1 %, dvsm tess=16 0.031 % (csm: 0.031 %). Bounds about 3x; tess must at least halve it.
TEST(DualParaboloid, ShadowsMatchHardRayTracingAndTessHelps) {
  Scene scene = test::small_scene("default", 160, 120);
  scene.light.radius = 0.0f;
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult rt = test::run("rt", scene, g);
  const double plain = mismatch_rate(test::run("dsm:res=1024", scene, g).mask, rt.mask);
  const double tess = mismatch_rate(test::run("dsm:res=1024,tess=16", scene, g).mask, rt.mask);
  const double coarse = mismatch_rate(test::run("dsm:res=32", scene, g).mask, rt.mask);
  const double vsm = mismatch_rate(test::run("dvsm:res=1024,tess=16", scene, g).mask, rt.mask);
  RecordProperty("mismatch_dsm", std::to_string(plain));
  RecordProperty("mismatch_dsm_tess16", std::to_string(tess));
  RecordProperty("mismatch_dsm_res32", std::to_string(coarse));
  RecordProperty("mismatch_dvsm_tess16", std::to_string(vsm));
  EXPECT_LT(plain, 0.008);
  EXPECT_LT(tess, 0.0027);
  EXPECT_LT(tess, plain / 2.0);
  EXPECT_GT(coarse, plain);
  EXPECT_LT(vsm, 0.001);
}

// tess splits an edge by that edge alone, so neighbouring triangles split their shared edges
// alike and no crack opens between them: a closed mesh stays closed, every edge of the output
// shared by exactly two triangles (vertices compared bit for bit, as the rasterizer sees them).
// The first version split a triangle's longest image edge unless all three corners were behind
// the rim margin; an edge between two corners behind it has an image that never gets short, so
// triangles reaching towards the antipode split until the work guard stopped them, mid-way,
// next to neighbours that had split their shared edges: T-junctions, whose cracks let light
// through on room100k (c10 0.947 at tess=8; 0.998 now).
TEST(DualParaboloid, TessellationKeepsClosedMeshesClosed) {
  // A torus below the light (closed, triangles of several sizes and shapes), or a room around
  // the light (a box the light is inside: triangles reaching behind the face's rim margin,
  // towards the antipode, where images blow up).
  for (const bool room : {false, true}) {
  Mesh sphere;
  if (room)
    add_box(sphere, glm::translate(mat4(1.0f), vec3(0.3f, -0.2f, 0.1f)) *
                        glm::scale(mat4(1.0f), vec3(4.0f, 3.0f, 5.0f)));
  else
    add_torus(sphere, vec3(0.3f, -1.0f, 0.2f), glm::normalize(vec3(0.3f, 1.0f, 0.2f)), 0.7f,
              0.25f, 24, 10);
  MeshView view;
  view.positions = sphere.positions.data();
  view.vertex_count = sphere.positions.size();
  view.indices = sphere.indices.data();
  view.triangle_count = sphere.triangle_count();
  const FaceLayout L = dual_paraboloid_layout(256, 2);
  ParaboloidProjection pp;
  pp.right = L.faces[0].right;
  pp.up = L.faces[0].up;
  pp.forward = L.faces[0].forward;
  auto key = [](const vec3& v) {
    const vec3 z = v + vec3(0.0f);  // -0 and +0 are one point
    uint32_t b[3];
    std::memcpy(b, &z, sizeof b);
    return std::array<uint32_t, 3>{b[0], b[1], b[2]};
  };
  auto edges_of = [&](const std::vector<vec3>& pos) {
    std::map<std::pair<std::array<uint32_t, 3>, std::array<uint32_t, 3>>, int> edges;
    for (size_t t = 0; t + 2 < pos.size(); t += 3)
      for (int e = 0; e < 3; ++e) {
        auto a = key(pos[t + size_t(e)]), b = key(pos[t + size_t((e + 1) % 3)]);
        if (b < a) std::swap(a, b);
        ++edges[{a, b}];
      }
    return edges;
  };
  // The input is closed: every edge twice.
  std::vector<vec3> soup;
  for (uint32_t i : sphere.indices) soup.push_back(sphere.positions[i]);
  size_t open_input = 0;
  for (const auto& [e, n] : edges_of(soup)) open_input += n != 2 && e.first != e.second;
  ASSERT_EQ(open_input, 0u);
  for (const float max_texels : {16.0f, 4.0f}) {
    Tessellated t;
    tessellate(view, pp, 0.5f * float(paraboloid_face_edge(256)), max_texels, t);
    ASSERT_GT(t.positions.size(), 3 * 2 * sphere.triangle_count()) << max_texels;  // it split
    size_t open = 0;
    for (const auto& [e, n] : edges_of(t.positions)) open += n != 2 && e.first != e.second;
    EXPECT_EQ(open, 0u) << (room ? "room" : "torus") << " tess " << max_texels;
  }
  }
}

}  // namespace
}  // namespace shadowlab
