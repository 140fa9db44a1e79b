// Alpha-discard foliage (Krave) in both passes, against Embree's alpha filters and against
// analysis:
//  - an alpha-checkerboard quad between a point light and a floor casts a checkerboard shadow:
//    the expected visibility of every floor point comes from intersecting its ray to the light
//    with the quad's plane and reading the checker cell there (analysis, no renderer involved);
//    csm and the Embree reference must both match it at >= 99 % of the floor pixels away from
//    cell edges, and each other likewise;
//  - the camera pass of the foliage scene against Embree primary rays with the alpha filter;
//  - every map technique on the foliage scene: finite, and within its bound of the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "core/error.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"
#include "techniques/registry/technique.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

constexpr int kCells = 8;  // checker cells per side of the quad

// Floor 4 × 4 m at y = 0; a 1 × 1 m quad at y = 1 whose alpha is an 8 × 8 checkerboard (cell
// (i, j) transparent when i + j is even); point light at (0, 3, 0); camera looking down at an
// angle so it sees the floor around and through the quad.
Scene checker_scene(int w, int h) {
  Scene s;
  s.name = "checker";
  add_grid_quad(new_mesh(s, "floor", vec3(0.7f)), vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), 4, 4);
  Mesh& q = new_mesh(s, "checker", vec3(0.5f));
  q.positions = {{-0.5f, 1, 0.5f}, {0.5f, 1, 0.5f}, {0.5f, 1, -0.5f}, {-0.5f, 1, -0.5f}};
  q.normals.assign(4, vec3(0, 1, 0));
  q.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // u along +x, v along -z
  q.indices = {0, 1, 2, 0, 2, 3};
  ImageF tex(kCells, kCells, 4, 1.0f);
  for (int y = 0; y < kCells; ++y)
    for (int x = 0; x < kCells; ++x) tex.at(x, y, 3) = (x + y) % 2 == 0 ? 0.0f : 1.0f;
  s.textures.push_back(tex);
  s.materials[size_t(q.material)].alpha_texture = 0;
  s.light.position = vec3(0, 3, 0);
  s.light.radius = 0.0f;
  s.light.near = 0.05f;
  s.light.far = 10.0f;
  s.camera.eye = vec3(0, 4.5f, 2.5f);
  s.camera.target = vec3(0, 0, 0);
  s.camera.fov_y_deg = 45.0f;
  s.camera.width = w;
  s.camera.height = h;
  validate_scene(s, "checker scene");
  return s;
}

// Expected visibility of floor point p: its segment to the light crosses y = 1 at
// c = p + (L − p)·(1 − p.y)/(L.y − p.y); inside the quad, lit iff the cell is transparent.
// `edge` returns the distance (in cells) from c to the nearest cell boundary.
float expected_checker(const vec3& p, const vec3& light, double& edge) {
  const double t = (1.0 - double(p.y)) / (double(light.y) - double(p.y));
  const double cx = double(p.x) + (double(light.x) - double(p.x)) * t;
  const double cz = double(p.z) + (double(light.z) - double(p.z)) * t;
  const double u = cx + 0.5, v = 0.5 - cz;  // the quad's uv at c
  const double gu = u * kCells, gv = v * kCells;
  edge = std::min(std::fabs(gu - std::round(gu)), std::fabs(gv - std::round(gv)));
  if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0) return 1.0f;
  // Texel row from the top: v up (core/texture.h), so row = (kCells - 1) - floor(v·kCells).
  const int col = std::min(kCells - 1, int(gu)), row = kCells - 1 - std::min(kCells - 1, int(gv));
  return (col + row) % 2 == 0 ? 1.0f : 0.0f;
}

TEST(AlphaCheckerboard, ShadowMatchesAnalysisAndEmbreeAwayFromCellEdges) {
  const Scene s = checker_scene(320, 240);
  const GBuffer g = render_gbuffer(s);
  RunOptions opt;
  opt.want_texels = false;
  for (const char* spec : {"csm:res=1024,bias=0.005", "rt:hard=1"}) {
    const ShadowResult r = run_technique(parse_technique_spec(spec, "test"), s, g, opt);
    size_t kept = 0, agree = 0, shadowed = 0, under = 0;
    for (size_t i = 0; i < g.pixel_count(); ++i) {
      if (!g.covered[i] || g.mesh_id[i] != 0) continue;  // floor pixels only
      double edge = 0.0;
      const float want = expected_checker(g.position[i], s.light.position, edge);
      if (edge < 0.15) continue;  // within 0.15 cell of a boundary: texel and pixel rounding
      ++kept;
      const vec3& p = g.position[i];
      // Inside the quad's shadow footprint on the floor (the quad scaled by 3/2 from the light).
      if (std::fabs(p.x) < 0.75f && std::fabs(p.z) < 0.75f) ++under;
      shadowed += want == 0.0f;
      agree += (r.mask.data[i] > 0.5f) == (want > 0.5f);
    }
    // Not vacuous: the footprint is well sampled and about half of it (the opaque cells) is
    // in shadow.
    EXPECT_GT(under, size_t(1500)) << spec;
    EXPECT_GT(double(shadowed), 0.35 * double(under)) << spec;
    EXPECT_GE(double(agree), 0.99 * double(kept)) << spec << ": " << agree << " of " << kept;
    std::cout << "[ info     ] " << spec << ": " << agree << " of " << kept
              << " floor pixels away from cell edges match the analytic checker shadow ("
              << shadowed << " in shadow)\n";
  }
}

TEST(AlphaCheckerboard, CameraSeesTheFloorThroughTransparentCells) {
  // Pixels whose camera ray crosses the quad in a transparent cell show the floor (both in the
  // rasterizer and in Embree's primary rays with the alpha filter), opaque cells the quad.
  const Scene s = checker_scene(320, 240);
  const GBuffer g = render_gbuffer(s);
  const EmbreeScene rt(s);
  const PrimaryHits hits = primary_visibility(rt, s.camera);
  size_t covered = 0, same = 0, through = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) continue;
    ++covered;
    same += g.mesh_id[i] == hits.mesh_id[i] && g.prim_id[i] == hits.prim_id[i];
    // A floor pixel whose ray to the eye crosses y = 1 inside the quad: seen through a hole.
    if (g.mesh_id[i] == 0) {
      const vec3 p = g.position[i], e = s.camera.eye;
      const float t = (1.0f - p.y) / (e.y - p.y);
      const vec3 c = p + (e - p) * t;
      through += std::fabs(c.x) < 0.5f && std::fabs(c.z) < 0.5f;
    }
  }
  EXPECT_GE(double(same), 0.99 * double(covered)) << same << " of " << covered;
  EXPECT_GT(through, size_t(500)) << "the floor must be visible through the holes";
}

TEST(AlphaCheckerboard, CutoffOutsideUnitIntervalIsRejected) {
  Scene s = checker_scene(32, 24);
  s.materials[1].alpha_cutoff = 1.5f;
  EXPECT_THROW(validate_scene(s, "test"), InputError);
  s.materials[1].alpha_cutoff = std::nanf("");
  EXPECT_THROW(validate_scene(s, "test"), InputError);
  // Cutoff 0 keeps every fragment (alpha >= 0 always): the quad is then an opaque occluder,
  // so no floor point under its whole shadow is lit.
  s.materials[1].alpha_cutoff = 0.0f;
  const GBuffer g = render_gbuffer(s);
  RunOptions opt;
  const ShadowResult r = run_technique(parse_technique_spec("csm:res=512", "test"), s, g, opt);
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i] || g.mesh_id[i] != 0) continue;
    const vec3& p = g.position[i];
    // Inside the quad's shadow footprint (|x|, |z| < 0.75·0.9 to stay off its border).
    if (std::fabs(p.x) < 0.67f && std::fabs(p.z) < 0.67f) {
      EXPECT_EQ(r.mask.data[i], 0.0f) << i;
    }
  }
}

// --- The foliage scene ---

const Scene& foliage(int w, int h) {
  static Scene s;
  if (s.meshes.empty()) s = make_builtin_scene("foliage");
  apply_camera_size(s, w, h);
  return s;
}

TEST(Foliage, CameraPassMatchesEmbreePrimaryRaysWithTheAlphaFilter) {
  const Scene& s = foliage(512, 384);
  const GBuffer g = render_gbuffer(s);
  const EmbreeScene rt(s);
  const PrimaryHits hits = primary_visibility(rt, s.camera);
  size_t covered = 0, same = 0, leaves = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) continue;
    ++covered;
    same += g.mesh_id[i] == hits.mesh_id[i] && g.prim_id[i] == hits.prim_id[i];
    leaves += s.materials[size_t(s.meshes[g.mesh_id[i]].material)].alpha_texture >= 0;
  }
  EXPECT_GE(double(same), 0.99 * double(covered)) << same << " of " << covered;
  EXPECT_GT(leaves, covered / 20) << "alpha-tested leaves must be a fair part of the view";
  std::cout << "[ info     ] foliage camera pass: " << same << " of " << covered
            << " covered pixels on the same primitive as Embree (" << leaves << " on leaves)\n";
}

TEST(Foliage, EveryMapTechniqueIsFiniteAndWithinItsBoundOfTheReference) {
  const Scene& s = foliage(256, 192);
  const GBuffer g = render_gbuffer(s);
  RunOptions opt;
  opt.want_texels = false;
  const ShadowResult ref = run_technique(parse_technique_spec("rt:hard=1", "test"), s, g, opt);
  // Bounds on the share of pixels whose visibility differs by more than 0.5 from the hard
  // reference. At 256×192 a 1024 map has several texels per pixel, so only pixels along leaf-
  // shadow edges and the thinnest leaves' shadows may flip: depth maps within 2.5 %; the
  // filtered maps (3-texel blur) soften every edge further: 3 %. The control — the same csm
  // with the leaves as opaque cards in the map — must differ from the reference at least
  // 2.5× as often as the alpha-tested csm, so the test sees the cut-outs.
  struct Case {
    const char* spec;
    double bound;
  };
  const Case cases[] = {{"csm:res=1024", 0.025}, {"tsm:res=1024", 0.025}, {"cvsm:res=1024", 0.03},
                        {"tvsm:res=1024", 0.03},  {"cesm:res=1024", 0.03}, {"tesm:res=1024", 0.03}};
  size_t shadowed = 0;
  for (float v : ref.mask.data) shadowed += v < 0.5f;
  ASSERT_GT(shadowed, g.pixel_count() / 20) << "the scene must show shadows";
  double csm_share = 1.0;
  for (const Case& c : cases) {
    const ShadowResult r = run_technique(parse_technique_spec(c.spec, "test"), s, g, opt);
    size_t bad = 0, nonfinite = 0;
    for (size_t i = 0; i < g.pixel_count(); ++i) {
      nonfinite += !std::isfinite(r.mask.data[i]);
      bad += std::fabs(r.mask.data[i] - ref.mask.data[i]) > 0.5f;
    }
    EXPECT_EQ(nonfinite, 0u) << c.spec;
    const double share = double(bad) / double(g.pixel_count());
    EXPECT_LE(share, c.bound) << c.spec;
    if (std::string(c.spec).rfind("csm", 0) == 0) csm_share = share;
    std::cout << "[ info     ] foliage " << c.spec << ": " << 100.0 * share << " % of pixels differ\n";
  }
  // Control: leaves as opaque cards in the shadow map only (the GBuffer keeps the cut-outs).
  Scene opaque = s;
  for (Material& m : opaque.materials) m.alpha_texture = -1;
  const ShadowResult r = run_technique(parse_technique_spec("csm:res=1024", "test"), opaque, g, opt);
  size_t bad = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) bad += std::fabs(r.mask.data[i] - ref.mask.data[i]) > 0.5f;
  EXPECT_GT(double(bad) / double(g.pixel_count()), 2.5 * csm_share) << "opaque cards must cast card shadows";
  std::cout << "[ info     ] foliage csm with opaque cards: "
            << 100.0 * double(bad) / double(g.pixel_count()) << " % of pixels differ\n";
}

}  // namespace
}  // namespace shadowlab
