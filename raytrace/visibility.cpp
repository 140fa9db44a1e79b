#include "raytrace/visibility.h"

#include "raytrace/face_rays.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"

namespace shadowlab {
namespace {

constexpr int kPixelTile = 8;                 // tiles of kPixelTile × kPixelTile pixels, one task each
constexpr size_t kStreamCapacity = 2048;  // rays per rtcOccluded1M call (bounds scratch memory)

struct TileGrid {
  int width, height, tiles_x, tiles_y;
  explicit TileGrid(int w, int h)
      : width(w), height(h), tiles_x((w + kPixelTile - 1) / kPixelTile), tiles_y((h + kPixelTile - 1) / kPixelTile) {}
  size_t count() const { return size_t(tiles_x) * size_t(tiles_y); }
  int x0(size_t t) const { return int(t % size_t(tiles_x)) * kPixelTile; }
  int y0(size_t t) const { return int(t / size_t(tiles_x)) * kPixelTile; }
  int x1(size_t t) const { return std::min(x0(t) + kPixelTile, width); }
  int y1(size_t t) const { return std::min(y0(t) + kPixelTile, height); }
};

void check_gbuffer(const GBuffer& g) {
  SL_CHECK(g.width >= 0 && g.height >= 0);
  const size_t n = g.pixel_count();
  SL_CHECK_EQ(g.position.size(), n);
  SL_CHECK_EQ(g.geo_normal.size(), n);
  SL_CHECK_EQ(g.covered.size(), n);
}

RTCRay make_ray(vec3 org, vec3 dir, float tnear, float tfar) {
  RTCRay r;
  r.org_x = org.x;
  r.org_y = org.y;
  r.org_z = org.z;
  r.tnear = tnear;
  r.dir_x = dir.x;
  r.dir_y = dir.y;
  r.dir_z = dir.z;
  r.time = 0.0f;
  r.tfar = tfar;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  return r;
}

// A batch of shadow rays, each tagged with the tile-local pixel it belongs to; flush() traces
// them as one Embree stream and adds the unoccluded ones to that pixel's count.
struct ShadowStream {
  RTCScene scene;
  std::vector<RTCRay> rays;
  std::vector<uint16_t> owner;
  int* visible;  // per tile-local pixel

  ShadowStream(RTCScene s, int* visible_counts) : scene(s), visible(visible_counts) {
    rays.reserve(kStreamCapacity);
    owner.reserve(kStreamCapacity);
  }
  void add(const RTCRay& r, int local_pixel) {
    rays.push_back(r);
    owner.push_back(uint16_t(local_pixel));
    if (rays.size() == kStreamCapacity) flush();
  }
  void flush() {
    if (rays.empty()) return;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // shadow rays of a tile converge on the light
    rtcOccluded1M(scene, &ctx, rays.data(), unsigned(rays.size()), sizeof(RTCRay));
    // An occluded ray comes back with tfar = -inf.
    for (size_t i = 0; i < rays.size(); ++i)
      if (rays[i].tfar >= 0.0f) ++visible[owner[i]];
    rays.clear();
    owner.clear();
  }
};

// Fills the mask for every pixel that needs no ray (uncovered: 1, facing away: 0) and returns
// true for the pixels that need shadow rays.
// The rays of every tile, summed in tile order (the same total for any thread count).
uint64_t sum_tile_rays(const std::vector<uint32_t>& tile_rays) {
  uint64_t total = 0;
  for (uint32_t r : tile_rays) total += r;
  return total;
}

bool needs_rays(const GBuffer& g, size_t p, vec3 light, ImageF& mask) {
  if (!g.covered[p]) {
    mask.data[p] = 1.0f;
    return false;
  }
  if (!(glm::dot(g.geo_normal[p], light - g.position[p]) > 0.0f)) {
    mask.data[p] = 0.0f;  // facing away (also catches a NaN normal)
    return false;
  }
  return true;
}

// Counter-based stream of one pixel: value k of stream `dim` is mix64(key ^ k·φ64) with
// key = rng_hash(pixel, 0, seed, dim) — a pure function of (pixel, seed, dim, k), computed with
// one mix per value instead of rng_hash's four.
struct PixelStream {
  uint64_t key;
  PixelStream(uint64_t pixel, uint64_t seed, uint64_t dim) : key(rng_hash(pixel, 0, seed, dim)) {}
  uint64_t operator()(uint64_t k) const { return mix64(key ^ (k * 0x9E3779B97F4A7C15ull)); }
};

// Uniform integer in [0, bound) from the top 32 bits of h (multiply-shift, no division).
inline uint32_t bounded(uint64_t h, uint32_t bound) {
  return uint32_t(((h >> 32) * uint64_t(bound)) >> 32);
}

// Multi-jittered sample layout for spp = m·n (see visibility.h).
struct MultiJitter {
  int spp, m, n;
  std::vector<uint32_t> perm_x;  // m permutations of length n (column i: sub-strata of x)
  std::vector<uint32_t> perm_y;  // n permutations of length m (row j: sub-strata of y)

  explicit MultiJitter(int samples) : spp(samples), m(1), n(samples) {
    for (int d = 1; int64_t(d) * d <= samples; ++d)
      if (samples % d == 0) m = d;
    n = samples / m;
    perm_x.resize(size_t(spp));
    perm_y.resize(size_t(spp));
  }

  // Fisher–Yates shuffles of every column's and row's sub-strata, from stream 2 of the pixel.
  void shuffle(uint64_t pixel, uint64_t seed) {
    const PixelStream rnd(pixel, seed, 2);
    uint64_t k = 0;
    auto permute = [&](uint32_t* out, int len) {
      for (int a = 0; a < len; ++a) out[a] = uint32_t(a);
      for (int a = len - 1; a > 0; --a) std::swap(out[a], out[bounded(rnd(k++), uint32_t(a + 1))]);
    };
    for (int i = 0; i < m; ++i) permute(&perm_x[size_t(i) * size_t(n)], n);
    for (int j = 0; j < n; ++j) permute(&perm_y[size_t(j) * size_t(m)], m);
  }

  // Sample s = j·m + i in [0,1)², cell (i, j): x lies in the 1-D stratum i·n + perm_x[i][j] of
  // spp, y in the stratum j·m + perm_y[j][i]; the jitter inside comes from stream 0 (both
  // coordinates from one 64-bit value: bits 40..63 and 16..39).
  void sample(int i, int j, const PixelStream& jitter, float& x, float& y) const {
    const uint64_t h = jitter(uint64_t(j) * uint64_t(m) + uint64_t(i));
    const float jx = rng_float(h), jy = rng_float(h << 24);
    const float inv = 1.0f / float(spp);
    x = (float(i * n + int(perm_x[size_t(i) * size_t(n) + size_t(j)])) + jx) * inv;
    y = (float(j * m + int(perm_y[size_t(j) * size_t(m) + size_t(i)])) + jy) * inv;
  }
};

// Orthonormal basis (t1, t2, w) around the unit vector w, continuous except at w.z = 0 sign
// flips (the branchless construction of Duff et al. 2017).
void basis_around(const dvec3& w, dvec3& t1, dvec3& t2) {
  const double sign = std::copysign(1.0, w.z);
  const double a = -1.0 / (sign + w.z);
  const double b = w.x * w.y * a;
  t1 = dvec3(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
  t2 = dvec3(b, sign + w.y * w.y * a, -w.y);
}

}  // namespace

float shadow_ray_offset(float scene_scale, vec3 p) {
  const float mag = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return 1e-4f * scene_scale + 1e-6f * mag;
}

ImageF hard_visibility(const EmbreeScene& rt, const Scene& scene, const GBuffer& gbuffer,
                       uint64_t* rays) {
  check_gbuffer(gbuffer);
  ImageF mask(gbuffer.width, gbuffer.height, 1, 1.0f);
  const TileGrid grid(gbuffer.width, gbuffer.height);
  const vec3 light = scene.light.position;
  const float scale = rt.scene_scale();
  auto* rtc_scene = static_cast<RTCScene>(rt.native_scene());
  std::vector<uint32_t> tile_rays(grid.count(), 0);

  parallel_for(0, grid.count(), [&](size_t t) {
    int visible[kPixelTile * kPixelTile] = {};
    ShadowStream stream(rtc_scene, visible);
    int local_index[kPixelTile * kPixelTile];
    int traced = 0;
    for (int y = grid.y0(t); y < grid.y1(t); ++y)
      for (int x = grid.x0(t); x < grid.x1(t); ++x) {
        const size_t p = size_t(y) * size_t(gbuffer.width) + size_t(x);
        if (!needs_rays(gbuffer, p, light, mask)) continue;
        const vec3 n = gbuffer.geo_normal[p];
        const float eps = shadow_ray_offset(scale, gbuffer.position[p]);
        const vec3 org = gbuffer.position[p] + eps * n;
        const vec3 to_light = light - org;
        const float dist = glm::length(to_light);
        if (!(dist - eps > 0.0f)) {  // light within eps of the surface: nothing fits between
          mask.data[p] = 1.0f;
          continue;
        }
        const int local = (y - grid.y0(t)) * kPixelTile + (x - grid.x0(t));
        local_index[traced++] = local;
        stream.add(make_ray(org, to_light / dist, 0.0f, dist - eps), local);
      }
    stream.flush();
    for (int k = 0; k < traced; ++k) {
      const int local = local_index[k];
      const size_t p = size_t(grid.y0(t) + local / kPixelTile) * size_t(gbuffer.width) +
                       size_t(grid.x0(t) + local % kPixelTile);
      mask.data[p] = visible[local] > 0 ? 1.0f : 0.0f;
    }
    tile_rays[t] = uint32_t(traced);
  });
  rt.throw_if_error("tracing hard shadow rays");
  if (rays) *rays = sum_tile_rays(tile_rays);
  return mask;
}

size_t visibility_work_units(int width, int height) { return TileGrid(width, height).count(); }

ImageF soft_visibility(const EmbreeScene& rt, const Scene& scene, const GBuffer& gbuffer, int spp,
                       uint64_t seed, ProgressLine* progress, uint64_t* rays) {
  if (spp < 1) throw InputError("spp", "samples per pixel must be >= 1, got " + std::to_string(spp));
  const double radius = double(scene.light.radius);
  if (radius <= 0.0) return hard_visibility(rt, scene, gbuffer);
  check_gbuffer(gbuffer);

  ImageF mask(gbuffer.width, gbuffer.height, 1, 1.0f);
  const TileGrid grid(gbuffer.width, gbuffer.height);
  const vec3 light = scene.light.position;
  const dvec3 centre(light);
  const float scale = rt.scene_scale();
  auto* rtc_scene = static_cast<RTCScene>(rt.native_scene());
  constexpr float kTwoPi = 6.28318530717958647692f;
  std::vector<uint32_t> tile_rays(grid.count(), 0);

  parallel_for(0, grid.count(), [&](size_t t) {
    uint32_t cast = 0;
    int visible[kPixelTile * kPixelTile] = {};
    bool traced[kPixelTile * kPixelTile] = {};
    ShadowStream stream(rtc_scene, visible);
    MultiJitter mj(spp);
    for (int y = grid.y0(t); y < grid.y1(t); ++y)
      for (int x = grid.x0(t); x < grid.x1(t); ++x) {
        const size_t p = size_t(y) * size_t(gbuffer.width) + size_t(x);
        if (!needs_rays(gbuffer, p, light, mask)) continue;
        const vec3 n = gbuffer.geo_normal[p];
        const float eps = shadow_ray_offset(scale, gbuffer.position[p]);
        const vec3 org = gbuffer.position[p] + eps * n;
        const dvec3 to_centre = centre - dvec3(org);
        const double d = glm::length(to_centre);
        if (d <= radius) {  // inside the light: documented as fully lit
          mask.data[p] = 1.0f;
          continue;
        }
        const int local = (y - grid.y0(t)) * kPixelTile + (x - grid.x0(t));
        traced[local] = true;

        // Cone of directions subtended by the sphere: sin θmax = r/d. 1 − cos θmax is computed
        // as s²/(1 + √(1 − s²)) to keep its precision for small, distant lights.
        const dvec3 w = to_centre / d;
        dvec3 t1, t2;
        basis_around(w, t1, t2);
        const double s2 = (radius / d) * (radius / d);
        const double one_minus_cos_max = s2 / (1.0 + std::sqrt(1.0 - s2));

        // Per-sample work in float: the direction ends up in float anyway.
        const vec3 w_f(w), t1_f(t1), t2_f(t2);
        const float d_f = float(d), r2 = float(radius * radius);
        const float omc_max = float(one_minus_cos_max);
        mj.shuffle(p, seed);
        const PixelStream jitter(p, seed, 0);
        for (int j = 0; j < mj.n; ++j)
          for (int i = 0; i < mj.m; ++i) {
            float u1, u2;
            mj.sample(i, j, jitter, u1, u2);
            // Uniform in solid angle: 1 − cos θ uniform on [0, 1 − cos θmax], φ uniform.
            const float omc = u1 * omc_max;
            const float cos_t = 1.0f - omc;
            const float sin_t = std::sqrt(std::max(0.0f, omc * (2.0f - omc)));
            const float phi = kTwoPi * u2;
            const vec3 dir = t1_f * (sin_t * std::cos(phi)) + t2_f * (sin_t * std::sin(phi)) + w_f * cos_t;
            if (!(glm::dot(dir, n) > 0.0f)) continue;  // below the receiver's tangent plane
            // Distance to the near side of the sphere along dir.
            const float h = d_f * sin_t;
            const float t_hit = d_f * cos_t - std::sqrt(std::max(0.0f, r2 - h * h));
            const float tfar = t_hit - eps;
            if (!(tfar > 0.0f)) {  // the light touches the surface here: nothing fits between
              ++visible[local];
              continue;
            }
            stream.add(make_ray(org, dir, 0.0f, tfar), local);
            ++cast;
          }
      }
    stream.flush();
    for (int local = 0; local < kPixelTile * kPixelTile; ++local) {
      if (!traced[local]) continue;
      const size_t p = size_t(grid.y0(t) + local / kPixelTile) * size_t(gbuffer.width) +
                       size_t(grid.x0(t) + local % kPixelTile);
      mask.data[p] = float(visible[local]) / float(spp);
    }
    tile_rays[t] = cast;
    if (progress) progress->advance();
  });
  rt.throw_if_error("tracing soft shadow rays");
  if (rays) *rays = sum_tile_rays(tile_rays);
  return mask;
}

PrimaryHits primary_visibility(const EmbreeScene& rt, const Camera& camera) {
  // The camera's own matrices, so the rays go through exactly the pixel centres the
  // rasterizer samples; hits count from the near to the far plane.
  return perspective_rays(rt, camera_view(camera), camera_projection(camera), camera.width,
                          camera.height, camera.far);
}

}  // namespace shadowlab
