#pragma once
// Ray-traced visibility masks (the reference every technique is measured against) and primary
// visibility (to cross-check the rasterizer's GBuffer). Masks are W×H, one channel, 1 = lit.
//
// Conventions shared by the hard and the soft mask, per GBuffer pixel:
//  - not covered: 1;
//  - facing away: 0 when dot(geo_normal, light.position − P) <= 0. geo_normal is used as the
//    GBuffer stores it (the camera pass orients it toward the camera eye);
//  - else shadow rays leave from O = P + eps·geo_normal (eps: shadow_ray_offset) with tnear = 0
//    and tfar = (distance from O to the light point) − eps, so neither the receiver's own
//    triangle nor geometry touching the light's surface counts as an occluder.
// Rays are traced per 8×8 pixel tile as Embree ray streams (rtcOccluded1M, coherent flag, up to
// 2048 rays per call), tiles in parallel; every random number is a function of (pixel, sample,
// seed) only, so the output is bit-identical for any thread count.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/progress.h"
#include "core/scene.h"
#include "raytrace/embree_scene.h"

namespace shadowlab {

// Self-intersection offset (metres) for a shadow ray leaving surface point p:
//   eps = 1e-4 · scene_scale + 1e-6 · max(|p.x|, |p.y|, |p.z|).
// Why it scales: the GBuffer point and Embree's hit test both carry float rounding error that
// grows with the size of the triangles and of the coordinates, so a fixed eps would either
// leak light at contacts in a millimetre scene or cause acne in a kilometre one. The second
// term (≈ 8 float ulps of the coordinate) covers geometry far from the origin, where the
// coordinate's own spacing exceeds 1e-4 · scene_scale.
float shadow_ray_offset(float scene_scale, vec3 p);

// Hard shadows from the point light at scene.light.position (its radius is ignored): one ray
// per covered, light-facing pixel; 1 if unoccluded, 0 if occluded. `rays`, when given, receives
// the rays cast.
ImageF hard_visibility(const EmbreeScene& rt, const Scene& scene, const GBuffer& gbuffer,
                       uint64_t* rays = nullptr);

// Soft shadows from the sphere light (centre scene.light.position, radius scene.light.radius).
// Per covered, light-facing pixel: the fraction of `spp` shadow rays that reach the sphere.
//  - Directions are sampled uniformly in solid angle over the cone the sphere subtends at O
//    (exact: cos θ uniform on [cos θmax, 1], φ uniform), so the result converges to the
//    unoccluded fraction of the light's visible solid angle.
//  - Stratification: multi-jittered sampling on an m×n grid, m = the largest divisor of spp not
//    above √spp, n = spp/m: each of the m×n cells of the (1 − cos θ, φ) square holds one sample
//    AND each coordinate alone hits each of its spp 1-D strata exactly once (so spp needs not
//    be square; a prime spp still gets spp 1-D strata per axis). Random numbers: per pixel
//    p = y·W + x and stream dim (0: jitter, 2: shuffles) a key rng_hash(p, 0, seed, dim), and
//    value k of the stream is mix64(key ^ k·0x9E3779B97F4A7C15) — a pure function of
//    (pixel, seed, dim, k), never of the thread.
//  - A direction with dot(dir, geo_normal) <= 0 counts as not visible (the receiver blocks it).
//  - O inside the sphere (|C − O| <= radius): fully lit (1), since the pixel faces the centre.
//  - radius == 0: identical to hard_visibility (spp and seed are unused).
// Throws InputError for spp < 1.
// `progress`, when given, advances by one unit per finished tile; `rays`, when given, receives
// the rays cast (samples decided without a ray, below the tangent plane or where the light
// touches the surface, are not rays).
ImageF soft_visibility(const EmbreeScene& rt, const Scene& scene, const GBuffer& gbuffer, int spp,
                       uint64_t seed, ProgressLine* progress = nullptr, uint64_t* rays = nullptr);
// Number of units soft_visibility advances a ProgressLine by for a width × height GBuffer.
size_t visibility_work_units(int width, int height);

// Closest hits of one camera ray per pixel centre.
struct PrimaryHits {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> mesh_id;  // index into Scene::meshes, kNoPrimitive where nothing is hit
  std::vector<uint32_t> prim_id;  // triangle index within that mesh, kNoPrimitive where empty
  std::vector<float> depth;       // view-space distance along −z, metres; +inf where empty
};

// Casts the ray through the centre (x + 0.5, y + 0.5) of every pixel of a camera.width ×
// camera.height image (origin top-left, y down), matching camera_view / camera_projection:
// looks down −z, vertical fov camera.fov_y_deg, aspect width/height. Only hits with depth in
// [camera.near, camera.far] count (the rasterizer's clip range). Alpha-tested meshes are tested
// as in the shadow rays; no back-face culling.
PrimaryHits primary_visibility(const EmbreeScene& rt, const Camera& camera);

}  // namespace shadowlab
