#include "raster/gbuffer_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/block_bounds.h"
#include "core/parallel.h"
#include "raster/alpha_test.h"
#include "core/isa.h"
#include "raster/gbuffer_resolve_simd.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

// Camera rays through pixel centres: dir has a unit forward component, so the ray parameter of
// a hit is its view depth (distance along -z in view space).
struct PixelRays {
  vec3 eye, forward, right, up;
  float sx, sy;  // tan(fov/2)·aspect and tan(fov/2)
  int width, height;
  explicit PixelRays(const Camera& c) : eye(c.eye), width(c.width), height(c.height) {
    forward = glm::normalize(c.target - c.eye);
    right = glm::normalize(glm::cross(forward, c.up));
    up = glm::cross(right, forward);
    sy = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    sx = sy * float(c.width) / float(c.height);
  }
  // forward + (nx·sx)·right: the column's part of dir, glm's first sum.
  vec3 column(int x) const {
    const float nx = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
    return forward + (nx * sx) * right;
  }
  vec3 dir(int x, int y) const {
    const float ny = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;
    return column(x) + (ny * sy) * up;
  }
};

// Lane k of the mixed-triangle SIMD resolve: the triangle's vertices.
void fill_lane(ResolveLanes8& l, int k, const vec3* v) {
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) l.v[j][c][k] = v[j][c];
}

}  // namespace

GBuffer render_gbuffer(const Scene& scene, RasterStats* stats) {
  GBuffer g;
  render_gbuffer(scene, g, stats, true);
  return g;
}

void render_gbuffer(const Scene& scene, GBuffer& g, RasterStats* stats, bool allow_simd) {
  const Camera& cam = scene.camera;
  const int w = cam.width, h = cam.height;
  g.reshape(w, h);
  // Visibility pass: depth and triangle id only (the depth-only fast path). The target is
  // per calling thread and kept between calls: no page faults in timing loops.
  // (Bound to a plain reference: the worker threads below must see THIS thread's target, not
  // their own thread_local instance.)
  thread_local DepthTarget vis_storage;
  DepthTarget& vis = vis_storage;
  vis.with_ids = true;
  DepthOnlyShader shader;
  const mat4 view_proj = camera_projection(cam) * camera_view(cam);
  // Alpha-textured meshes discard their cut-out fragments (raster/alpha_test.h).
  const RasterStats st = rasterize_alpha(scene_mesh_views(scene), scene_alpha(scene), view_proj,
                                         CullMode::None, w, h, vis, shader);
  if (stats) *stats = st;

  // Resolve, once per pixel: intersect the pixel's camera ray with the visible triangle's
  // plane (view depth, position) and orient its normal. Every pixel is written, covered or
  // not. The interpolated attributes (shading normal, uv) are deferred: only the pictures for
  // people read them, and writing them cost a fifth of this pass (core/gbuffer_shading.h).
  const std::vector<uint32_t> first = scene_first_triangles(scene);
  const PixelRays rays(cam);
  const GBufferResolveKernels& kernels =
      gbuffer_resolve_kernels(allow_simd ? process_isa() : Isa::scalar);
  const ResolveRun8Fn simd = kernels.run8;
  const ResolveLanes8Fn lanes8 = kernels.lanes8;
  const ResolveLanes16Fn lanes16 = kernels.lanes16;
  // Every column's part of the ray direction, for the AVX2 paths (ResolveRun8::columns).
  std::vector<float> columns(3 * size_t(w));
  for (int x = 0; x < w; ++x) {
    const vec3 c = rays.column(x);
    for (int k = 0; k < 3; ++k) columns[size_t(k) * size_t(w) + size_t(x)] = c[k];
  }
  // Chunks of one block row each: a chunk also leaves the position bounds of its blocks
  // (GBuffer::block_bounds), from the positions while they are in registers.
  g.block_bounds.assign(size_t(g.blocks_x()) * size_t(g.blocks_y()), BlockBounds{});
  parallel_for_chunks(size_t(h), size_t(kGBufferBlock), [&](size_t y0, size_t y1) {
    uint32_t m = 0;
    struct {
      uint32_t t = kNoPrimitive, m = 0, p = 0;
      vec3 v[3]{vec3(0.0f), vec3(0.0f), vec3(0.0f)};
      bool has_terms = false;  // e1 .. e2q computed for v
      vec3 e1{0.0f}, e2{0.0f}, gn{0.0f};
      float e2q = 0.0f;
    } tri;
    ResolveRun8 run;  // the SIMD path's copy of the cached triangle's terms
    uint32_t run_t = kNoPrimitive;
    // The chunk is one block row: its bounds are accumulated row by row below.
    BlockRowBounds bounds;
    bounds.reset(g.blocks_x());
    // Neighbouring pixels mostly see the same triangle: its vertices are kept, and its terms
    // once computed (the mixed 8-pixel groups compute them in the kernel instead).
    auto load_triangle = [&](uint32_t t) {
      if (t == tri.t) return;
      if (t < first[m] || t >= first[m + 1])
        m = uint32_t(std::upper_bound(first.begin(), first.end(), t) - first.begin()) - 1;
      tri.t = t;
      tri.m = m;
      const Mesh& mesh = scene.meshes[m];
      tri.p = t - first[m];
      const uint32_t* idx = &mesh.indices[3 * size_t(tri.p)];
      for (int j = 0; j < 3; ++j) tri.v[j] = mesh.positions[idx[j]];
      tri.has_terms = false;
    };
    // The loaded triangle's terms (resolve_lanes8's LaneTriangles repeats these operations).
    auto triangle_terms = [&] {
      if (tri.has_terms) return;
      tri.has_terms = true;
      const vec3& p0 = tri.v[0];
      tri.e1 = tri.v[1] - p0;
      tri.e2 = tri.v[2] - p0;
      // Möller–Trumbore's e2·q with s = eye − p0 and q = s × e1: the ray parameter's numerator.
      tri.e2q = glm::dot(tri.e2, glm::cross(rays.eye - p0, tri.e1));
      const vec3 n = glm::cross(tri.e1, tri.e2);
      const float nl = glm::length(n);
      tri.gn = nl > 0.0f ? n / nl : vec3(0.0f, 1.0f, 0.0f);
    };
    // The camera's part of the SIMD paths' terms (ResolveRun8), the same for every pixel.
    run.eye = rays.eye;
    run.forward = rays.forward;
    run.right = rays.right;
    run.up = rays.up;
    run.sx = rays.sx;
    run.sy = rays.sy;
    run.width = rays.width;
    run.height = rays.height;
    run.columns = columns.data();
    auto empty_pixel = [&](size_t i) {
      g.position[i] = vec3(0.0f);
      g.geo_normal[i] = vec3(0.0f);
      g.depth[i] = std::numeric_limits<float>::infinity();
      g.mesh_id[i] = g.prim_id[i] = kNoPrimitive;
      g.covered[i] = 0;
    };
    alignas(32) ResolveLanes8 lanes;
    alignas(64) ResolveLanes16 lanes_w{};  // zeros: lanes no pixel has filled yet are inert
    for (size_t y = y0; y < y1; ++y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = y * size_t(w) + size_t(x);
        const uint32_t t = vis.ids[i];
        if (lanes16 && x + 16 <= w) {
          // Sixteen pixels in AVX-512, each lane its own triangle's terms (runs of one
          // triangle filled at once), the same bits as the code below; then the empty lanes.
          const uint32_t* ids = &vis.ids[i];
          uint32_t covered = 0;
          uint32_t starts = kernels.lanes16_runs(ids, &covered);
          if (covered == 0) {
            for (int k = 0; k < 16; ++k) empty_pixel(i + size_t(k));
            x += 15;
            continue;
          }
          // Run by run, from the runs' first pixels (no loop over a run's pixels).
          while (starts != 0) {
            const int k = __builtin_ctz(starts);
            starts &= starts - 1u;
            const int k1 = starts ? __builtin_ctz(starts) : 16;
            const uint32_t tk = ids[k];
            if (tk != kNoPrimitive) {
              load_triangle(tk);
              triangle_terms();
              const uint32_t run_mask = ((1u << k1) - 1u) & ~((1u << k) - 1u);
              kernels.lanes16_fill(lanes_w, run_mask, tri.e1, tri.e2, tri.gn, tri.e2q, tri.m,
                                   tri.p);
            }
          }
          lanes_w.covered = covered;
          lanes16(run, lanes_w, x, int(y), &vis.inv_w[i], &g.position[i], &g.geo_normal[i],
                  &g.depth[i], &g.mesh_id[i], &g.prim_id[i], &g.covered[i]);
          x += 15;
          continue;
        }
        bool run8 = false;  // the 8 pixels from x show one triangle
        if (lanes8 && x + 8 <= w) {
          // The group's kind without a branch per pixel (loops with early exits were
          // mispredicted on the mixed groups): bit k for pixel x + k.
          const uint32_t* ids = &vis.ids[i];
          unsigned covered = 0, same = 0;
          for (int k = 0; k < 8; ++k) {
            covered |= unsigned(ids[k] != kNoPrimitive) << k;
            same |= unsigned(ids[k] == t) << k;
          }
          if (covered == 0) {
            for (int k = 0; k < 8; ++k) empty_pixel(i + size_t(k));
            x += 7;
            continue;
          }
          if ((covered & same) != 0xFFu) {
            // Eight pixels not all on one triangle: each lane its own triangle's terms, the
            // AVX2 path for all 8 (same bits as the code below), then the empty lanes' values.
            for (int k = 0; k < 8; ++k) {
              const uint32_t tk = vis.ids[i + size_t(k)];
              if (tk == kNoPrimitive) {
                fill_lane(lanes, k, tri.v);  // any finite values: overwritten below
                continue;
              }
              load_triangle(tk);
              fill_lane(lanes, k, tri.v);
              g.mesh_id[i + size_t(k)] = tri.m;
              g.prim_id[i + size_t(k)] = tri.p;
              g.covered[i + size_t(k)] = 1;
            }
            lanes8(run, lanes, x, int(y), &vis.inv_w[i], &g.position[i], &g.geo_normal[i],
                   &g.depth[i]);
            for (unsigned e = ~covered & 0xFFu; e != 0; e &= e - 1u)
              empty_pixel(i + size_t(__builtin_ctz(e)));
            x += 7;
            continue;
          }
          load_triangle(t);  // eight pixels on one triangle: the run below
          run8 = true;
        }
        if (simd && t != kNoPrimitive && x + 8 <= w &&
            (run8 || (t == tri.t && std::all_of(&vis.ids[i + 1], &vis.ids[i + 8],
                                                [t](uint32_t o) { return o == t; })))) {
          // Eight pixels on the cached triangle: the AVX2 path, same bits as the code below.
          if (run_t != t) {
            run_t = t;
            triangle_terms();
            run.e1 = tri.e1;
            run.e2 = tri.e2;
            run.gn = tri.gn;
            run.e2q = tri.e2q;
          }
          simd(run, x, int(y), &vis.inv_w[i], &g.position[i], &g.geo_normal[i], &g.depth[i]);
          for (size_t k = i; k < i + 8; ++k) {
            g.mesh_id[k] = tri.m;
            g.prim_id[k] = tri.p;
            g.covered[k] = 1;
          }
          x += 7;
          continue;
        }
        if (t == kNoPrimitive) {
          empty_pixel(i);
          continue;
        }
        load_triangle(t);
        triangle_terms();
        const vec3 d = rays.dir(x, int(y));
        // Möller–Trumbore's ray parameter without the inside test (the rasterizer decided
        // coverage); the terms that do not depend on the ray come from the triangle cache.
        const vec3 pv = glm::cross(d, tri.e2);
        const float det = glm::dot(tri.e1, pv);
        float depth = 1.0f / vis.inv_w[i];
        if (std::fabs(det) > 1e-30f) {
          const float tt = tri.e2q * (1.0f / det);
          // Only trust a hit in front of the eye; edge-on triangles keep the raster depth.
          if (std::isfinite(tt) && tt > 0.0f) depth = tt;
        }
        vec3 gn = tri.gn;
        const vec3 pos = rays.eye + depth * d;
        // Two-sided: the normal faces the eye.
        if (glm::dot(gn, cam.eye - pos) < 0.0f) gn = -gn;
        g.position[i] = pos;
        g.geo_normal[i] = gn;
        g.depth[i] = depth;
        g.mesh_id[i] = tri.m;
        g.prim_id[i] = tri.p;
        g.covered[i] = 1;
      }
      // The row's positions, back from L1 once the row is written (reading them right after
      // the SIMD path's vector stores would stall on store forwarding).
      bounds.add_row(&g.position[y * size_t(w)], &g.covered[y * size_t(w)], w);
    }
    bounds.store(g, int(y0) / kGBufferBlock);
  });
}

}  // namespace shadowlab
