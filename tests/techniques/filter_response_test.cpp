// Filter responses with expected values from analysis: PCF weights over a hand-made step edge
// (cube map and face-map family), the VSM variance floor and light-bleeding reduction and the
// ESM exponential over a flat occluder, and the tetrahedral tie-break. Every map here is
// either filled by hand or holds one plane, so each expected value is a closed form.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "scenes/mesh_builders.h"
#include "techniques/pipeline/light_map.h"
#include "techniques/lookup/map_receiver.h"
#include "test_scenes.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

// Light at the origin, range 10 m, nothing in the scene (maps are filled by hand).
Scene empty_light_scene() {
  Scene s;
  s.materials.push_back(Material{});
  s.light.position = vec3(0.0f);
  s.light.near = 0.05f;
  s.light.far = 10.0f;
  return s;
}

// A GBuffer of hand-placed receivers at `points`, each facing the light (normal towards it).
GBuffer receivers(const std::vector<vec3>& points, const vec3& light) {
  GBuffer g;
  g.resize(int(points.size()), 1);
  for (size_t i = 0; i < points.size(); ++i) {
    g.position[i] = points[i];
    g.normal[i] = g.geo_normal[i] = glm::normalize(light - points[i]);
    g.covered[i] = 1;
  }
  return g;
}

// PCF over a step edge. The stored distance is 0.05 (an occluder at 0.5 m) in texel columns
// x < edge and +inf (nothing) from column `edge` on; the receiver's distance is 0.2, between
// the two, and no bias applies. An N×N PCF at continuous coordinate sx reads columns
// bx - h .. bx + h + 1 (bx = floor(sx - 0.5), h = (N-1)/2) with weights (1 - f, 1, ..., 1, f)/N,
// f = sx - 0.5 - bx, and rows likewise (their weights sum to 1); the lit share is the sum of
// the column weights at x >= edge. pcf = 1 is the nearest texel: lit iff floor(sx) >= edge.
double expected_pcf(double sx, int pcf, int edge) {
  if (pcf <= 1) return std::floor(sx) >= edge ? 1.0 : 0.0;
  const int h = (pcf - 1) / 2;
  const double bx = std::floor(sx - 0.5), f = sx - 0.5 - bx;
  double lit = 0.0;
  for (int i = 0; i <= pcf; ++i) {
    const double w = i == 0 ? 1.0 - f : (i == pcf ? f : 1.0);
    if (int(bx) - h + i >= edge) lit += w;
  }
  return lit / pcf;
}

// Sub-texel positions across the edge at column 4 of an 8-texel face, rows 4.6 (interior).
const double kSx[] = {2.7, 3.3, 3.8, 4.05, 4.3, 4.5, 4.95, 5.6};

TEST(FilterResponse, CubeMapPcfWeightsOverAStepEdge) {
  // csm's own mechanism: no guard band, taps beyond a face looked up in its neighbour.
  const Scene scene = empty_light_scene();
  const int res = 8, face = 3, edge = 4;  // face -Y
  LightMap map;
  MapParams p = default_map_params(FaceLayoutKind::Cube, MapFilter::Depth);
  p.res = res;
  p.bias = p.slope = 0.0f;
  ASSERT_EQ(p.seams, SeamMode::Cross);
  map.layout = map_layout(p, scene);
  ASSERT_EQ(map.layout.faces[0].width, res);
  // Every face is empty (+inf, lit) but for the occluded columns of face -Y, so taps that cross
  // into a neighbouring face (pcf 5 at sx 5.6 reads column 8) count as lit, as analysed.
  map.dist.distance.assign(kCubeFaces, LineAlignedFloats(size_t(res * res), std::numeric_limits<float>::infinity()));
  map.dist.rendered.assign(kCubeFaces, true);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < edge; ++x) map.dist.distance[face][size_t(y * res + x)] = 0.05f;
  std::vector<vec3> pts;
  for (double sx : kSx) {
    // Texel coordinates → face coordinates u = sx/res·2 − 1, v = 1 − sy/res·2; a receiver 2 m
    // along that direction (distance / far = 0.2).
    const vec3 dir = cube_face_direction(face, float(sx / res * 2.0 - 1.0), float(1.0 - 4.6 / res * 2.0));
    pts.push_back(2.0f * dir);
  }
  // 16 pixels: the SIMD kernel (pcf=1) takes whole groups of 8.
  for (double sx : kSx) pts.push_back(2.0f * cube_face_direction(face, float(sx / res * 2.0 - 1.0), 0.1f));
  const GBuffer g = receivers(pts, scene.light.position);
  for (int pcf : {1, 3, 5}) {
    p.pcf = pcf;
    ImageF mask;
    lookup_light_map(scene, g, p, map, mask, nullptr);
    for (size_t i = 0; i < pts.size(); ++i) {
      EXPECT_NEAR(mask.data[i], expected_pcf(kSx[i % 8], pcf, edge), 5e-7)
          << "pcf " << pcf << " sx " << kSx[i % 8];
    }
  }
}

TEST(FilterResponse, FaceMapPcfWeightsOverAStepEdgeOnEveryLayout) {
  const Scene scene = empty_light_scene();
  for (int pcf : {1, 3, 5}) {
    for (const bool tetra : {false, true}) {
      MapParams p = default_map_params(tetra ? FaceLayoutKind::Tetrahedron : FaceLayoutKind::Cube,
                                       MapFilter::Depth);
      p.seams = SeamMode::Guard;
      p.pcf = pcf;
      p.res = 16;
      p.bias = p.slope = 0.0f;
      LightMap map;
      map.layout = map_layout(p, scene);
      const int face = tetra ? 0 : 3;
      const LightFace& f = map.layout.faces[size_t(face)];
      // The edge and the receivers sit mid-face, in the face image's own texel coordinates.
      const int edge = f.width / 2, row = f.height / 2;
      const size_t nf = map.layout.faces.size();
      map.dist.distance.assign(nf, {});
      map.dist.rendered.assign(nf, false);
      map.dist.rendered[size_t(face)] = true;
      LineAlignedFloats& d = map.dist.distance[size_t(face)];
      d.assign(f.texel_count(), std::numeric_limits<float>::infinity());
      for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < edge; ++x) d[size_t(y * f.width + x)] = 0.05f;
      std::vector<vec3> pts;
      std::vector<double> sxs;
      for (double sx : kSx) {
        sxs.push_back(sx - 4.0 + edge);
        pts.push_back(2.0f * face_texel_direction(f, float(sxs.back()), float(row) + 0.6f));
      }
      const GBuffer g = receivers(pts, scene.light.position);
      ImageF mask;
      lookup_light_map(scene, g, p, map, mask, nullptr);
      for (size_t i = 0; i < pts.size(); ++i) {
        EXPECT_NEAR(mask.data[i], expected_pcf(sxs[i], pcf, edge), 1e-6)
            << (tetra ? "tetra" : "cube") << " pcf " << pcf << " sx " << sxs[i];
      }
    }
  }
}

// A large occluder plane 1 m below the light (y = -1) over receivers 2 m below it (y = -2): on
// every ray the occluder is at half the receiver's distance r, so t − μ = r/2 (metres). The
// plane's own spread inside a 3-texel footprint is ~1e-7 m², far below the floors used here.
// At res 256 the footprint's curvature moves the mean by ~3e-5 of the gap: measured largest
// errors 3.1e-5 (VSM) and 3.0e-5 (ESM), bounds 1e-4. PCF: 1.7e-7 (cube) and 3.2e-7 (face
// maps, float texel coordinates through a direction and back), bounds 5e-7 and 1e-6.
struct PlaneCase {
  Scene scene;
  GBuffer g;
  std::vector<double> r;  // receiver distances, metres
};

PlaneCase occluder_plane() {
  PlaneCase c;
  c.scene = empty_light_scene();
  Mesh& m = new_mesh(c.scene, "occluder", vec3(0.5f));
  add_grid_quad(m, vec3(-4.0f, -1.0f, 4.0f), vec3(8.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, -8.0f), 4, 4);
  std::vector<vec3> pts;
  for (const vec2 xz : {vec2(0.0f, 0.0f), vec2(0.05f, 0.03f), vec2(-0.3f, 0.2f), vec2(0.6f, -0.45f)}) {
    pts.push_back(vec3(xz.x, -2.0f, xz.y));
    c.r.push_back(std::sqrt(double(xz.x) * xz.x + 4.0 + double(xz.y) * xz.y));
  }
  c.g = receivers(pts, c.scene.light.position);
  return c;
}

TEST(FilterResponse, VsmVarianceFloorAndBleedReductionOverAFlatOccluder) {
  const PlaneCase c = occluder_plane();
  // σ² = min_variance = 0.25 m² dominates: p = σ²/(σ² + (r/2)²) (the units cancel), and the
  // bleeding reduction maps it to (p − b)/(1 − b), clamped to [0, 1].
  for (const char* layout : {"cvsm", "tvsm"})
    for (const char* extra : {"", ",fp32=1"})
      for (double bleed : {0.0, 0.1, 0.5}) {
        const std::string spec = std::string(layout) + ":res=256,min_variance=0.25,bleed=" +
                                 std::to_string(bleed) + extra;
        const ShadowResult res = test::run(spec, c.scene, c.g);
        for (size_t i = 0; i < c.r.size(); ++i) {
          const double gap = c.r[i] / 2.0;
          const double p = 0.25 / (0.25 + gap * gap);
          const double want = std::clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
          EXPECT_NEAR(res.mask.data[i], want, 1e-4) << spec << " receiver " << i;
        }
      }
  // Without a floor the plane's own tiny variance gives an almost black shadow.
  for (const char* spec : {"cvsm:res=256,min_variance=0", "tvsm:res=256,min_variance=0"}) {
    const ShadowResult res = test::run(spec, c.scene, c.g);
    for (size_t i = 0; i < c.r.size(); ++i) EXPECT_LT(res.mask.data[i], 5e-5f) << spec;
  }
}

TEST(FilterResponse, EsmOverAFlatOccluderIsTheExponentialOfTheGap) {
  // visibility = exp(c·(z_occ − t)) with z_occ − t = −(r/2)/far.
  const PlaneCase c = occluder_plane();
  for (const char* layout : {"cesm", "tesm"})
    for (double k : {5.0, 20.0}) {
      const std::string spec = std::string(layout) + ":res=256,c=" + std::to_string(k);
      const ShadowResult res = test::run(spec, c.scene, c.g);
      for (size_t i = 0; i < c.r.size(); ++i) {
        EXPECT_NEAR(res.mask.data[i], std::exp(-k * c.r[i] / 2.0 / 10.0), 1e-4)
            << spec << " receiver " << i;
      }
    }
}

// EVSM over the same plane: receiver t = r/far, occluder z = (r/2)/far, far = 10 m. Each warp
// (v₊ = e^(c₊(2d−1)), v₋ = −e^(−c₋(2d−1))) gives p = σ²/(σ² + (v(t) − v(z))²) with the floor
// σ² = (min_variance/far²)·(dv/dt)², dv/dt = 2c·e^(±c(2t−1)); 4 moments take the smaller p.
double evsm_closed_form(double r, double c_pos, double c_neg, double min_var, bool four) {
  const double far = 10.0, t = r / far, z = r / 2.0 / far, mv = min_var / (far * far);
  auto bound = [&](double c, double sign) {
    const double et = std::exp(sign * c * (2.0 * t - 1.0));
    const double ez = std::exp(sign * c * (2.0 * z - 1.0));
    const double var = mv * (2.0 * c * et) * (2.0 * c * et);
    const double gap = sign * et - sign * ez;
    return var / (var + gap * gap);
  };
  const double pos = bound(c_pos, 1.0);
  return four ? std::min(pos, bound(c_neg, -1.0)) : pos;
}

TEST(FilterResponse, EvsmOverAFlatOccluderIsChebyshevInEachWarp) {
  const PlaneCase c = occluder_plane();
  double worst = 0.0;
  for (const char* layout : {"cevsm", "tevsm"})
    for (const int moments : {2, 4})
      for (const double cp : {5.0, 20.0, 44.0})
        for (const double mv : {0.01, 0.25}) {
          const std::string spec = fmt::format("{}:res=256,moments={},c_pos={:g},c_neg=3,min_variance={:g}",
                                               layout, moments, cp, mv);
          const ShadowResult res = test::run(spec, c.scene, c.g);
          for (size_t i = 0; i < c.r.size(); ++i) {
            const double want = evsm_closed_form(c.r[i], cp, 3.0, mv, moments == 4);
            worst = test::worst_of(worst, std::fabs(double(res.mask.data[i]) - want));
            EXPECT_NEAR(res.mask.data[i], want, 1e-4) << spec << " receiver " << i;
          }
        }
  RecordProperty("worst_error", std::to_string(worst));
}

TEST(FilterResponse, TetrahedralTiesGoToTheLowerFace) {
  // Exact ties of dot(dir, normal) (every product below is exact in float): (0, -1, 0) is
  // 1/√3 from faces 0 and 1; (0, 1, 0) is 1/√3 from faces 2 and 3; (-1, 0, 1) is √(2/3) from
  // faces 0 and 2; (1, 0, -1) is √(2/3) from faces 1 and 3.
  const FaceLayout L = tetra_layout(64, 2);
  EXPECT_EQ(face_of(L, vec3(0.0f, -1.0f, 0.0f)), 0);
  EXPECT_EQ(face_of(L, vec3(0.0f, 1.0f, 0.0f)), 2);
  EXPECT_EQ(face_of(L, vec3(-1.0f, 0.0f, 1.0f)), 0);
  EXPECT_EQ(face_of(L, vec3(1.0f, 0.0f, -1.0f)), 1);
  // The lookup uses the same rule: a receiver on the tie direction lands in the lower face.
  const MapParams p = default_map_params(FaceLayoutKind::Tetrahedron, MapFilter::Depth);
  PointLight light;
  const Receiver r = make_receiver(L, light, p, 1.0f, 0.1f, vec3(0.0f, -2.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(r.face, 0);
  const Receiver r2 = make_receiver(L, light, p, 1.0f, 0.1f, vec3(0.0f, 3.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(r2.face, 2);
}

// Progress lines appear only for builds expected to take seconds: a 4096 VSM with a 63-texel
// blur (~100 M texels × 63) yes, the default maps no.
TEST(LightMapProgress, OnlyLongBuildsShowAProgressLine) {
  const Scene scene = empty_light_scene();
  auto needs = [&](const char* spec, FaceLayoutKind layout, MapFilter filter) {
    const MapParams p = parse_map_params(parse_technique_spec(spec, "t"), layout, filter, "t");
    return light_map_needs_progress(p, map_layout(p, scene));
  };
  EXPECT_TRUE(needs("cvsm:res=4096,blur=63", FaceLayoutKind::Cube, MapFilter::Variance));
  EXPECT_FALSE(needs("cvsm:res=1024", FaceLayoutKind::Cube, MapFilter::Variance));
  EXPECT_FALSE(needs("csm:res=4096", FaceLayoutKind::Cube, MapFilter::Depth));
  EXPECT_FALSE(needs("tesm:res=512,blur=9", FaceLayoutKind::Tetrahedron, MapFilter::Exponential));
}

}  // namespace
}  // namespace shadowlab
