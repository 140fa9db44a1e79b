#include "techniques/cube_shadow_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/timer.h"
#include "raster/alpha_test.h"
#include "raster/pipeline.h"
#include "techniques/cube_lookup_simd.h"
#include "techniques/depth_quantize.h"
#include "techniques/normal_offset.h"

namespace shadowlab {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Continuous texel coordinates (x right, y down, texel centres at +0.5) of direction `dir`
// from the light in `face`.
vec2 face_texel_coords(int face, const vec3& dir, int res) {
  const vec2 uv = cube_face_uv(face, dir);
  return vec2((uv.x * 0.5f + 0.5f) * float(res), (0.5f - uv.y * 0.5f) * float(res));
}

// Texel of a continuous coordinate, clamped to the face. Truncation equals floor here: they
// differ only for negative non-integers, which the clamp maps to texel 0 either way (and
// floorf is a long libm-style sequence on the SSE2 baseline: it was a third of the lookup).
int clamp_texel(float c, int res) {
  return std::clamp(int(std::max(c, -1.0f)), 0, res - 1);
}

// Visits the texels of a lookup: calls fn(face, x, y, weight) for each, weights summing to 1.
// Texels outside the face are redirected through their direction to the face that owns it.
template <class Fn>
void for_each_tap(int res, int face, vec2 st, int pcf, Fn&& fn) {
  if (pcf <= 1) {
    fn(face, clamp_texel(st.x, res), clamp_texel(st.y, res), 1.0f);
    return;
  }
  const float gx = st.x - 0.5f, gy = st.y - 0.5f;
  // floor for |g| < 2^31 without libm: truncate, then step down for negative non-integers.
  auto floor_int = [](float g) {
    const int i = int(g);
    return float(i) > g ? i - 1 : i;
  };
  const int bx = floor_int(gx), by = floor_int(gy);
  const float fx = gx - float(bx), fy = gy - float(by);
  const int half = (pcf - 1) / 2;
  const float norm = 1.0f / float(pcf * pcf);
  for (int j = 0; j <= pcf; ++j) {
    const float wy = j == 0 ? 1.0f - fy : (j == pcf ? fy : 1.0f);
    for (int i = 0; i <= pcf; ++i) {
      const float wx = i == 0 ? 1.0f - fx : (i == pcf ? fx : 1.0f);
      const float w = wx * wy * norm;
      if (w == 0.0f) continue;
      const int tx = bx - half + i, ty = by - half + j;
      if (tx >= 0 && ty >= 0 && tx < res && ty < res) {
        fn(face, tx, ty, w);
        continue;
      }
      // Cross-face tap: the texel centre's direction picks the owning face.
      const float u = (float(tx) + 0.5f) / float(res) * 2.0f - 1.0f;
      const float v = 1.0f - (float(ty) + 0.5f) / float(res) * 2.0f;
      const vec3 dir = cube_face_direction(face, u, v);
      const int f2 = cube_face_of(dir);
      const vec2 st2 = face_texel_coords(f2, dir, res);
      fn(f2, clamp_texel(st2.x, res), clamp_texel(st2.y, res), w);
    }
  }
}

}  // namespace

CubeShadowParams parse_cube_params(const TechniqueSpec& spec, const char* flag) {
  SpecReader r(spec, flag);
  CubeShadowParams p;
  p.res = r.get_int("res", p.res, 1, 8192);
  p.pcf = r.get_int("pcf", p.pcf, 1, 15);
  p.bias = float(r.get_double("bias", p.bias, 0.0, 1e3));
  p.slope = float(r.get_double("slope", p.slope, 0.0, 1e3));
  p.normal = float(r.get_double("normal", p.normal, 0.0, 1e3));
  p.depth = depth_format_from_name(r.get_choice("depth", "f32", depth_format_names()));
  r.reject_unknown();
  if (p.pcf > 1 && p.pcf % 2 == 0)
    throw InputError(flag, spec.name + ": 'pcf' must be 1 or odd, got " + std::to_string(p.pcf));
  return p;
}

static void set_view_projs(const PointLight& light, CubeShadowMap& map) {
  const mat4 proj = cube_face_projection(light);
  for (int f = 0; f < kCubeFaces; ++f) map.view_proj[f] = proj * cube_face_view(light, f);
}

std::array<bool, kCubeFaces> cube_faces_needed(const Scene& scene, const GBuffer& g,
                                               const CubeShadowParams& p) {
  // Per-chunk flags, merged in chunk order.
  const size_t grain = 8192;
  const size_t chunks = (g.pixel_count() + grain - 1) / grain;
  std::vector<std::array<bool, kCubeFaces>> flags(chunks, std::array<bool, kCubeFaces>{});
  parallel_for_chunks(g.pixel_count(), grain, [&](size_t b, size_t e) {
    std::array<bool, kCubeFaces>& f = flags[b / grain];
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i] || !faces_light(g, i, scene.light.position)) continue;
      const vec3 dir = normal_offset_point(g.position[i], g.geo_normal[i], scene.light.position,
                                           p.normal, 2.0f / float(p.res)) -
                       scene.light.position;
      const int face = cube_face_of(dir);
      if (p.pcf <= 1) {
        f[face] = true;
        continue;
      }
      const vec2 st = face_texel_coords(face, dir, p.res);
      for_each_tap(p.res, face, st, p.pcf,
                   [&](int ff, int, int, float) { f[ff] = true; });
    }
  });
  std::array<bool, kCubeFaces> needed{};
  for (const auto& f : flags)
    for (int i = 0; i < kCubeFaces; ++i) needed[i] = needed[i] || f[i];
  return needed;
}

namespace {

// One row of the epilogue below. Branch-free so it vectorizes: an empty texel (1/w = 0)
// divides to +inf, "nothing seen". Compiled twice (AVX2 and baseline, chosen at run time);
// sqrt, multiply and divide are exact IEEE operations, so both clones give the same bits.
__attribute__((target_clones("avx2", "default"))) void radial_row(const float* src, float* dst,
                                                                 int x0, int x1, float v,
                                                                 float scale, float inv_far) {
  for (int x = x0; x < x1; ++x) {
    const float u = (float(x) + 0.5f) * scale - 1.0f;
    dst[x] = std::sqrt(1.0f + u * u + v * v) * inv_far / src[x];
  }
}

// Depth-only shader whose tile epilogue turns 1/w into normalised radial distance: the ray
// through texel centre (u, v) has direction (u, v, -1) in view space (tan 45° = 1), so
// |p - L| = view depth × sqrt(1 + u² + v²).
struct RadialDepthShader {
  static constexpr bool kNeedsAttributes = false;
  static constexpr bool kKeepsAll = true;
  int res;
  float inv_far;
  float* out;  // res², row-major; may alias the depth target (each texel is read, then written)
  bool operator()(const Fragment&) const { return true; }
  void finish_tile(int x0, int y0, int x1, int y1, const DepthTarget& depth) const {
    const float scale = 2.0f / float(res);
    for (int y = y0; y < y1; ++y) {
      const float v = 1.0f - (float(y) + 0.5f) * scale;
      const float* src = depth.inv_w.data() + size_t(y) * size_t(res);
      float* dst = out + size_t(y) * size_t(res);
      radial_row(src, dst, x0, x1, v, scale, inv_far);
    }
  }
};

}  // namespace

void render_cube_map(const Scene& scene, const std::array<bool, kCubeFaces>& needed, int res,
                     CubeShadowMap& map, size_t* submitted, size_t* culled, CullMode cull) {
  map.res = res;
  set_view_projs(scene.light, map);
  const std::vector<MeshView> meshes = scene_mesh_views(scene);
  const AlphaScene alpha = scene_alpha(scene);  // leaves (Krave) cast cut-out shadows
  // The faces are independent. For scenes of moderate size they render concurrently (each
  // face's binning and tiles are parallel loops of their own, so the scheduler balances faces
  // of unequal cost: room100k 19.1 -> 17.2 ms at 2 threads). With ~1M triangles the six binned
  // frames alive at once cost more in cache and memory traffic than the balance gains
  // (room1m 93 -> 106 ms), so those render one face after the other. Stats are summed in face
  // order; no output depends on the schedule.
  constexpr size_t kConcurrentFacesMaxTriangles = 250000;
  const bool concurrent = scene.triangle_count() <= kConcurrentFacesMaxTriangles;
  std::array<RasterStats, kCubeFaces> stats{};
  for (int f = 0; f < kCubeFaces; ++f) {
    map.rendered[f] = needed[f];
    if (!needed[f]) map.depth[f].clear();
  }
  auto render_face = [&](size_t fi) {
    const int f = int(fi);
    if (!needed[f]) return;
    // Rasterize straight into the face's storage and convert 1/w to radial distance in place
    // (tile epilogue): one res² buffer per face.
    DepthTarget target;
    target.inv_w.swap(map.depth[f]);
    target.resize(res, res);
    RadialDepthShader shader{res, 1.0f / scene.light.far, target.inv_w.data()};
    stats[f] = rasterize_alpha(meshes, alpha, map.view_proj[f], cull, res, res, target, shader);
    target.inv_w.swap(map.depth[f]);
  };
  if (concurrent)
    parallel_for(0, kCubeFaces, render_face);
  else
    for (size_t f = 0; f < size_t(kCubeFaces); ++f) render_face(f);
  for (const RasterStats& st : stats) {
    if (submitted) *submitted += st.triangles_in;
    if (culled) *culled += st.culled_frustum;
  }
}

void lookup_cube_map(const Scene& scene, const GBuffer& g, const CubeShadowMap& map,
                     const CubeShadowParams& p, ImageF& mask, ImageU32* texels) {
  const PointLight& light = scene.light;
  // Every pixel is written below.
  shape_single_channel(mask, g.width, g.height);
  if (texels) shape_single_channel(*texels, g.width, g.height);
  const int res = map.res;
  const float inv_far = 1.0f / light.far;
  // World size of one texel at unit distance along the face axis (face spans [-1, 1]).
  const float texel_angle = 2.0f / float(res);
  // PCF compares the receiver's depth with texels up to (pcf+1)/2 texels away, on a plane
  // tilted by the angle to the light, so the slope term grows with the footprint radius.
  const float footprint = 0.5f * float(p.pcf + 1);
  // The AVX2 path for pcf=1 (its scalar oracle is the loop body below).
  const CubeLookup8Fn simd = p.pcf <= 1 && p.normal <= 0.0f ? cube_lookup8_simd() : nullptr;
  CubeLookupConsts consts{light.position, inv_far, p.bias, p.slope * footprint * texel_angle, res, {}};
  for (int f = 0; f < kCubeFaces; ++f)
    consts.face_depth[f] = map.depth[f].empty() ? nullptr : map.depth[f].data();
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    if (simd)
      for (; b + 8 <= e; b += 8)
        simd(consts, &g.position[b].x, &g.geo_normal[b].x, &g.covered[b], &mask.data[b],
             texels ? &texels->data[b] : nullptr);
    for (size_t i = b; i < e; ++i) {
      if (texels) texels->data[i] = kNoTexel;
      if (!g.covered[i]) {
        mask.data[i] = 1.0f;
        continue;
      }
      if (!faces_light(g, i, light.position)) {
        mask.data[i] = 0.0f;
        continue;
      }
      // faces_light() is false at the light itself (N·0 = 0), so the distance is > 0 here.
      const vec3 to_p0 = g.position[i] - light.position;
      const float dist0 = glm::length(to_p0);
      // The slope term keeps the receiver's own angle; the lookup uses the offset point.
      const float cos_t = std::clamp(glm::dot(g.geo_normal[i], -to_p0) / dist0, 1e-4f, 1.0f);
      vec3 to_p = to_p0;
      float dist = dist0;
      if (p.normal > 0.0f) {
        to_p = normal_offset_point(g.position[i], g.geo_normal[i], light.position, p.normal,
                                   texel_angle) - light.position;
        dist = glm::length(to_p);
      }
      const int face = cube_face_of(to_p);
      const vec2 st = face_texel_coords(face, to_p, res);
      if (texels)
        texels->data[i] = uint32_t(face) * uint32_t(res) * uint32_t(res) +
                          uint32_t(clamp_texel(st.y, res)) * uint32_t(res) +
                          uint32_t(clamp_texel(st.x, res));
      // Bias in metres, then normalised like the stored distances.
      const float tan_t = std::min(std::sqrt(1.0f - cos_t * cos_t) / cos_t, 10.0f);
      const float bias = p.bias + p.slope * footprint * texel_angle * dist * tan_t;
      const float receiver = (dist - bias) * inv_far;
      // Lit weight over total weight: both sums see the same additions, so an all-lit
      // footprint gives exactly 1 whatever the float rounding of the weights.
      float lit = 0.0f, total = 0.0f;
      for_each_tap(res, face, st, p.pcf, [&](int f, int x, int y, float w) {
        total += w;
        lit += receiver <= map.depth[f][size_t(y) * size_t(res) + size_t(x)] ? w : 0.0f;
      });
      mask.data[i] = total > 0.0f ? std::min(lit / total, 1.0f) : 1.0f;
    }
  });
}

ShadowResult run_cube_shadow_map(const TechniqueSpec& spec, const Scene& scene,
                                 const GBuffer& gbuffer, const RunOptions& options) {
  const CubeShadowParams p = parse_cube_params(spec, options.flag);
  ShadowResult r;
  r.faces_total = kCubeFaces;
  CubeShadowMap map;
  std::array<bool, kCubeFaces> needed{};
  std::vector<double> map_t, lookup_t;
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    size_t submitted = 0, culled = 0;
    auto t0 = std::chrono::steady_clock::now();
    needed = cube_faces_needed(scene, gbuffer, p);
    render_cube_map(scene, needed, p.res, map, &submitted, &culled);
    for (int f = 0; f < kCubeFaces; ++f)
      if (map.rendered[size_t(f)])
        quantize_depths(map.depth[size_t(f)].data(), map.depth[size_t(f)].size(), p.depth);
    map_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    lookup_cube_map(scene, gbuffer, map, p, r.mask, options.want_texels ? &r.texels : nullptr);
    lookup_t.push_back(ms_since(t0));
    r.triangles_submitted = submitted;
    r.triangles_culled = culled;
  }
  r.map_ms = median(map_t);
  r.lookup_ms = median(lookup_t);
  for (bool n : needed) r.faces_needed += n ? 1 : 0;
  r.faces_rendered = r.faces_needed;
  r.notes = "faces " + std::to_string(r.faces_rendered) + "/6 rendered, " +
            std::to_string(r.triangles_culled) + " of " + std::to_string(r.triangles_submitted) +
            " triangle submissions culled before binning";
  return r;
}

}  // namespace shadowlab
