// Stage 2 of the light-map pipeline (techniques/pipeline/faces_needed.h): the block bounds the camera
// pass leaves, the box test that decides a whole block, and the faces-needed set with blocks
// against a brute-force walk of every pixel and every tap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "techniques/pipeline/faces_needed.h"
#include "techniques/pipeline/light_map.h"
#include "techniques/lookup/map_receiver.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

// The camera pass leaves, per 16×16 block, the min and max of its covered positions; the
// image height 120 is not a multiple of 16, so the last block row is partial.
TEST(FacesNeeded, BlockBoundsAreTheCoveredPositionsBounds) {
  int empty = 0, blocks = 0;
  // The default view covers every block; from 6x as far away the scene fills only part of
  // the image, so empty blocks occur too.
  for (const float distance : {1.0f, 6.0f}) {
    SCOPED_TRACE(distance);
    Scene scene = test::small_scene("default", 152, 120);
    scene.camera.eye = scene.camera.target + distance * (scene.camera.eye - scene.camera.target);
    scene.camera.far *= distance;
    const GBuffer g = render_gbuffer(scene);
    ASSERT_TRUE(g.has_block_bounds());
    ASSERT_EQ(g.block_bounds.size(), size_t(10 * 8));
    for (int by = 0; by < g.blocks_y(); ++by)
      for (int bx = 0; bx < g.blocks_x(); ++bx) {
        vec3 lo(1e30f), hi(-1e30f);
        bool any = false;
        for (int y = by * 16; y < std::min(g.height, by * 16 + 16); ++y)
          for (int x = bx * 16; x < std::min(g.width, bx * 16 + 16); ++x) {
            const size_t i = size_t(y) * size_t(g.width) + size_t(x);
            if (!g.covered[i]) continue;
            any = true;
            for (int k = 0; k < 3; ++k) {
              lo[k] = std::min(lo[k], g.position[i][k]);
              hi[k] = std::max(hi[k], g.position[i][k]);
            }
          }
        const BlockBounds& b = g.block_bounds[size_t(by * g.blocks_x() + bx)];
        ASSERT_EQ(b.empty(), !any) << bx << "," << by;
        empty += !any;
        ++blocks;
        if (any) {
          EXPECT_EQ(b.lo, lo) << bx << "," << by;
          EXPECT_EQ(b.hi, hi) << bx << "," << by;
        }
      }
    GBuffer copy = g;
    copy.resize(8, 8);
    EXPECT_FALSE(copy.has_block_bounds());  // a rewritten GBuffer gets no stale bounds
  }
  // Both kinds of block occur, so neither case is vacuous.
  EXPECT_GT(empty, 0);
  EXPECT_LT(empty, blocks);
}

// Every point of a decided box (grown by `reach`) maps to the decided face, with its whole PCF
// footprint inside that face's image for cross-face PCF; random lights and boxes, from points to
// boxes a metre wide, on every layout. Both answers must occur, so the test is not vacuous.
TEST(FacesNeeded, EveryPointOfADecidedBoxMapsToItsFace) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  auto in = [&](float a, float b) { return a + (b - a) * u01(rng); };
  const struct { FaceLayout layout; int cross_pcf; } layouts[] = {
      {cube_layout(64, 0), 1}, {cube_layout(64, 0), 3}, {cube_layout(16, 0), 5},
      {tetra_layout(64, 3), 1}, {dual_paraboloid_layout(64, 2), 1}};
  for (const auto& c : layouts) {
    int decided = 0, undecided = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      const vec3 light(in(-3, 3), in(-3, 3), in(-3, 3));
      const vec3 centre = light + glm::normalize(vec3(in(-1, 1), in(-1, 1), in(-1, 1))) * in(0.05f, 6);
      const vec3 half = vec3(in(0, 1), in(0, 1), in(0, 1)) * std::pow(10.0f, in(-4, 0));
      const float reach = u01(rng) < 0.5f ? 0.0f : in(0, 0.05f);
      const int f = box_single_face(c.layout, light, centre - half, centre + half, reach, c.cross_pcf);
      if (f < 0) {
        ++undecided;
        continue;
      }
      ++decided;
      const LightFace& lf = c.layout.faces[size_t(f)];
      for (int s = 0; s < 40; ++s) {
        vec3 q;
        for (int k = 0; k < 3; ++k) {
          const float e = half[k] + reach;
          // The first 8 samples are the grown box's corners.
          q[k] = s < 8 ? centre[k] + (((s >> k) & 1) ? e : -e) : centre[k] + in(-e, e);
        }
        const vec3 d = q - light;
        ASSERT_EQ(face_of(c.layout, d), f) << "trial " << trial << " sample " << s;
        if (c.cross_pcf > 1) {
          ASSERT_TRUE(pcf_taps_inside(face_texel_coords(lf, d), c.cross_pcf, lf.width, lf.height))
              << "trial " << trial << " sample " << s;
        }
      }
    }
    EXPECT_GT(decided, 300);
    EXPECT_GT(undecided, 100);
  }
}

// Every point of a box said to miss a set of faces (grown by `reach`) maps to a face outside
// the set; random lights, boxes and sets on every layout but the projector's. Both answers must
// occur, and among the misses boxes that straddle faces (box_single_face undecided), which are
// the ones the block path gains from; every box that box_single_face decides is decided for
// the face its points map to (a face of its own is never missed).
TEST(FacesNeeded, EveryPointOfABoxThatMissesFacesMapsElsewhere) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  auto in = [&](float a, float b) { return a + (b - a) * u01(rng); };
  const FaceLayout layouts[] = {cube_layout(64, 0), tetra_layout(64, 3),
                                dual_paraboloid_layout(64, 2)};
  for (const FaceLayout& layout : layouts) {
    const uint32_t all = (1u << layout.faces.size()) - 1u;
    int misses = 0, straddling = 0, others = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      const vec3 light(in(-3, 3), in(-3, 3), in(-3, 3));
      const vec3 centre = light + glm::normalize(vec3(in(-1, 1), in(-1, 1), in(-1, 1))) * in(0.05f, 6);
      const vec3 half = vec3(in(0, 1), in(0, 1), in(0, 1)) * std::pow(10.0f, in(-3, 0));
      const float reach = u01(rng) < 0.5f ? 0.0f : in(0, 0.05f);
      // Any set: those holding a face of the box must not be missed, and half of the sets
      // leave the centre's face out, so that misses occur.
      uint32_t set = uint32_t(rng()) & all;
      if (u01(rng) < 0.5f) set &= ~(1u << face_of(layout, centre - light));
      if (set == 0) continue;  // nothing to miss
      if (!box_misses_faces(layout, light, centre - half, centre + half, reach, set)) {
        ++others;
        continue;
      }
      ++misses;
      const int single = box_single_face(layout, light, centre - half, centre + half, reach, 1);
      straddling += single < 0;
      if (single >= 0) {
        ASSERT_FALSE((set >> single) & 1u) << "trial " << trial;
      }
      for (int s = 0; s < 40; ++s) {
        vec3 q;
        for (int k = 0; k < 3; ++k) {
          const float e = half[k] + reach;
          q[k] = s < 8 ? centre[k] + (((s >> k) & 1) ? e : -e) : centre[k] + in(-e, e);
        }
        const int f = face_of(layout, q - light);
        ASSERT_FALSE((set >> f) & 1u) << "trial " << trial << " sample " << s << " face " << f;
      }
    }
    EXPECT_GT(misses, 300);
    EXPECT_GT(others, 200);
    // A box across the dual paraboloid's one boundary touches both of its faces.
    if (layout.kind != FaceLayoutKind::DualParaboloid) {
      EXPECT_GT(straddling, 50);
    }
  }
  Projector proj;
  proj.direction = vec3(1, 0, 0);
  EXPECT_FALSE(box_misses_faces(projector_layout(proj, 64, 0), vec3(0), vec3(5, 0, 0),
                                vec3(5, 0, 0), 0.0f, 1u));
}

// With cross seams a box grown by pcf_tap_reach holds its points' taps: when that grown box
// misses a set of faces, no tap of any sampled point reads one of them (for_each_pcf_tap from
// the point's face and texel coordinates). Coarse faces and wide footprints, so that taps reach
// past their points' faces; both answers must occur. Without the growth it fails: boxes near a
// boundary miss the set while their points' taps read it.
TEST(FacesNeeded, TapsOfABoxGrownByTheTapReachMissItsFaces) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  auto in = [&](float a, float b) { return a + (b - a) * u01(rng); };
  const struct { FaceLayout layout; int pcf; } cases[] = {
      {cube_layout(32, 0), 5}, {cube_layout(16, 0), 3}, {tetra_layout(32, 0), 3}};
  for (const auto& c : cases) {
    const uint32_t all = (1u << c.layout.faces.size()) - 1u;
    int misses = 0, others = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      const vec3 light(in(-3, 3), in(-3, 3), in(-3, 3));
      const vec3 centre = light + glm::normalize(vec3(in(-1, 1), in(-1, 1), in(-1, 1))) * in(0.5f, 6);
      const vec3 half = vec3(in(0, 1), in(0, 1), in(0, 1)) * std::pow(10.0f, in(-3, -1));
      BlockBounds box;
      box.lo = centre - half;
      box.hi = centre + half;
      uint32_t set = uint32_t(rng()) & all;
      set &= ~(1u << face_of(c.layout, centre - light));
      if (set == 0) continue;
      const float grown = pcf_tap_reach(c.layout, c.pcf, box, light, 0.0f);
      if (!box_misses_faces(c.layout, light, box.lo, box.hi, grown, set)) {
        ++others;
        continue;
      }
      ++misses;
      for (int s = 0; s < 24; ++s) {
        vec3 q;
        for (int k = 0; k < 3; ++k)
          q[k] = s < 8 ? centre[k] + (((s >> k) & 1) ? half[k] : -half[k]) : in(box.lo[k], box.hi[k]);
        const vec3 d = q - light;
        const int f = face_of(c.layout, d);
        const vec2 st = face_texel_coords(c.layout.faces[size_t(f)], d);
        for_each_pcf_tap(c.layout, f, st, c.pcf, [&](int ff, int, int, float) {
          ASSERT_FALSE((set >> ff) & 1u) << "trial " << trial << " sample " << s;
        });
      }
    }
    EXPECT_GT(misses, 200);
    EXPECT_GT(others, 200);
  }
}

// A point box well inside a face is decided; a box around the light or across a face boundary
// is not.
// The reaches a block's box is grown by, from their derivations: PCF taps lie within
// (pcf − 1)/2 + 1.5 texels of the lookup point on each face axis, so the box grows by
// √2·((pcf − 1)/2 + 2) plane texels (half a texel to spare) times the far corner's distance from
// the light, and 1 % for rounding; the normal offset moves a point by at most normal × plane
// texel × its distance, plus 1 %; neither grows a box without the feature.
TEST(FacesNeeded, ReachesFollowTheirDerivations) {
  const FaceLayout cube = cube_layout(32, 0);
  const double texel = 2.0 / 32.0;  // the cube face's plane [−1, 1] over 32 texels
  BlockBounds box;
  box.lo = vec3(1.0f, 2.0f, -3.0f);
  box.hi = vec3(1.5f, 2.5f, -2.0f);
  const vec3 light(0.5f, 0.0f, 0.0f);
  const double far = std::sqrt(1.0 * 1.0 + 2.5 * 2.5 + 3.0 * 3.0);  // |(1.5, 2.5, −3) − L|
  EXPECT_EQ(pcf_tap_reach(cube, 1, box, light, 0.0f), 0.0f);
  for (const int pcf : {3, 5, 7})
    EXPECT_NEAR(pcf_tap_reach(cube, pcf, box, light, 0.0f), 1.01 * std::sqrt(2.0) * ((pcf - 1) / 2 + 2) * texel * far,
                1e-5) << pcf;
  // A box already grown by the normal offset's reach r: its points are up to far + r away.
  EXPECT_NEAR(pcf_tap_reach(cube, 3, box, light, 0.25f), 1.01 * std::sqrt(2.0) * 3 * texel * (far + 0.25), 1e-5);
  MapParams p;
  p.normal = 0.0f;
  EXPECT_EQ(normal_offset_reach(p, float(texel), box, light), 0.0f);
  for (const float normal : {0.5f, 1.0f, 2.0f}) {
    p.normal = normal;
    EXPECT_NEAR(normal_offset_reach(p, float(texel), box, light), 1.01 * normal * texel * far, 1e-5) << normal;
  }
}

TEST(FacesNeeded, BoxTestDecidesInteriorsOnly) {
  const FaceLayout cube = cube_layout(64, 0);
  const vec3 L(0.5f, 1.0f, -0.25f);
  const vec3 px = L + vec3(2.0f, 0.3f, -0.2f);
  EXPECT_EQ(box_single_face(cube, L, px, px, 0.0f, 1), 0);
  EXPECT_EQ(box_single_face(cube, L, px, px, 0.0f, 3), 0);
  EXPECT_EQ(box_single_face(cube, L, L - vec3(0.1f), L + vec3(0.1f), 0.0f, 1), -1);
  const vec3 edge = L + vec3(2.0f, 2.0f, 0.0f);  // on the +x / +y boundary
  EXPECT_EQ(box_single_face(cube, L, edge - vec3(0.01f), edge + vec3(0.01f), 0.0f, 1), -1);
  // 0.9 of the way to the +x face's edge: decided alone, not once the normal offset's reach
  // or a 5×5 footprint at res 16 (2.5 texels of the 8-texel half-face) crosses it.
  const vec3 near_edge = L + vec3(2.0f, 1.8f, 0.0f);
  EXPECT_EQ(box_single_face(cube, L, near_edge, near_edge, 0.0f, 1), 0);
  EXPECT_EQ(box_single_face(cube, L, near_edge, near_edge, 0.3f, 1), -1);
  EXPECT_EQ(box_single_face(cube_layout(16, 0), L, near_edge, near_edge, 0.0f, 5), -1);
  const vec3 inf(std::numeric_limits<float>::infinity());
  EXPECT_EQ(box_single_face(cube, L, -inf, inf, 0.0f, 1), -1);
}

// The rounding margin is per coordinate: a point is decided only when moving each coordinate of
// p − light by up to 1e-5 × scale (scale: the largest coordinate of the box plus the light's, plus
// the reach) keeps it on its face. Light (1, 0, 0), point (3, 2 − δ, 0.1): scale 4, so the margin
// is 4e-5 a coordinate; p − light = (2, 2 − δ, 0.1) is on the +x face, and x − y = δ. Moving x
// down and y up by the margin each closes a gap of 8e-5: δ = 6e-5 may cross to +y and stays
// undecided, δ = 1e-4 cannot and is decided.
TEST(FacesNeeded, BoxTestMarginIsPerCoordinate) {
  const FaceLayout cube = cube_layout(64, 0);
  const vec3 L(1.0f, 0.0f, 0.0f);
  const vec3 within(3.0f, 2.0f - 6e-5f, 0.1f), beyond(3.0f, 2.0f - 1e-4f, 0.1f);
  EXPECT_EQ(face_of(cube, within - L), 0);
  EXPECT_EQ(face_of(cube, within - L + vec3(-4e-5f, 4e-5f, 0.0f)), 2);
  EXPECT_EQ(box_single_face(cube, L, within, within, 0.0f, 1), -1);
  EXPECT_EQ(box_single_face(cube, L, beyond, beyond, 0.0f, 1), 0);
}

// The faces needed with block bounds equal a brute-force walk of every covered, light-facing
// pixel's lookup point and (cross-face PCF) every tap, for lights moved around the scene, every
// layout, PCF sizes and normal offsets. Enough of the cases need fewer than every face, so the
// block path (not only the sparse sample's early exit) decides them.
TEST(FacesNeeded, BlockPathEqualsABruteForceWalk) {
  const FaceLayoutKind C = FaceLayoutKind::Cube, T = FaceLayoutKind::Tetrahedron,
                       D = FaceLayoutKind::DualParaboloid;
  const struct { const char* spec; FaceLayoutKind layout; MapFilter filter; } specs[] = {
      {"csm:res=256", C, MapFilter::Depth},        {"csm:res=256,pcf=3", C, MapFilter::Depth},
      {"csm:res=32,pcf=5", C, MapFilter::Depth},   {"csm:res=64,normal=2", C, MapFilter::Depth},
      {"tsm:res=256", T, MapFilter::Depth},        {"tsm:res=64,pcf=3", T, MapFilter::Depth},
      {"dsm:res=256", D, MapFilter::Depth},        {"cvsm:res=128", C, MapFilter::Variance},
      // Offsets of metres: lookup points cross face boundaries their receivers do not.
      {"csm:res=64,normal=6", C, MapFilter::Depth}, {"csm:res=128,normal=12", C, MapFilter::Depth},
      {"csm:res=32,normal=5", C, MapFilter::Depth}, {"tsm:res=64,normal=6", T, MapFilter::Depth},
      // Wide footprints on coarse faces: taps reach faces no lookup point lies in, so a block
      // across known faces may still need another one through its taps.
      {"csm:res=8,pcf=7", C, MapFilter::Depth},    {"tsm:res=8,pcf=5", T, MapFilter::Depth}};
  const vec3 offsets[] = {vec3(0.0f), vec3(0.0f, -1.2f, 0.0f), vec3(1.5f, -1.0f, 0.5f),
                          vec3(-2.0f, 0.5f, -1.0f), vec3(0.3f, -1.7f, -0.4f)};
  int partial = 0, cases = 0;
  for (const char* scene_name : {"default", "foliage"}) {
    Scene scene = test::small_scene(scene_name, 160, 120);
    const vec3 light0 = scene.light.position;
    for (const vec3& off : offsets) {
      scene.light.position = light0 + off;
      const GBuffer g = render_gbuffer(scene);
      ASSERT_TRUE(g.has_block_bounds());
      for (const auto& c : specs) {
        const char* spec = c.spec;
        const MapParams p = parse_map_params(parse_technique_spec(spec, "--technique"), c.layout,
                                             c.filter, "--technique");
        const FaceLayout layout = map_layout(p, scene);
        const bool cross = p.filter == MapFilter::Depth && p.seams == SeamMode::Cross && p.pcf > 1;
        std::vector<bool> expected(layout.faces.size(), false);
        for (size_t i = 0; i < g.pixel_count(); ++i) {
          if (!g.covered[i] || !faces_light(g, i, scene.light.position)) continue;
          const vec3 to_p = lookup_point(layout, scene.light, p, g.position[i], g.geo_normal[i]) -
                            scene.light.position;
          const int face = face_of(layout, to_p);
          expected[size_t(face)] = true;
          if (cross)
            for_each_pcf_tap(layout, face, face_texel_coords(layout.faces[size_t(face)], to_p), p.pcf,
                             [&](int ff, int, int, float) { expected[size_t(ff)] = true; });
        }
        ++cases;
        partial += std::count(expected.begin(), expected.end(), true) < long(expected.size());
        EXPECT_EQ(faces_needed(scene, g, layout, p), expected)
            << scene_name << " " << spec << " light offset " << off.x << "," << off.y << "," << off.z;
      }
    }
  }
  EXPECT_GE(partial, cases / 4) << partial << " of " << cases;
}

}  // namespace
}  // namespace shadowlab
