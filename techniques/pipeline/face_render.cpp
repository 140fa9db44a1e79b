#include "techniques/pipeline/face_render.h"

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/isa.h"
#include "core/parallel.h"
#include "raster/alpha_test.h"
#include "raster/pipeline.h"
#include "techniques/pipeline/cube_faces.h"
#include "techniques/pipeline/face_rows.h"
#include "techniques/pipeline/paraboloid_tess.h"

namespace shadowlab {
namespace {

// Lowers *bits (a non-negative float's bits, which order as unsigned integers) to m's.
void atomic_min_float(std::atomic<uint32_t>& bits, float m) {
  const uint32_t mb = std::bit_cast<uint32_t>(m);
  uint32_t cur = bits.load(std::memory_order_relaxed);
  while (mb < cur && !bits.compare_exchange_weak(cur, mb, std::memory_order_relaxed)) {
  }
}

// Depth-only shader whose tile epilogue turns 1/w (reciprocal view depth) into normalised
// radial distance: the ray through a texel centre with plane coordinates (u, v) has view
// direction (u, v, -1), so |p - L| = view depth × sqrt(1 + u² + v²).
struct FaceRadialShader {
  static constexpr bool kNeedsAttributes = false;
  static constexpr bool kKeepsAll = true;
  const LightFace* face;
  float inv_far;
  std::atomic<uint32_t>* min_bits;  // the face's smallest distance so far (float bits), or null
  const FaceRowKernels* rows;  // the epilogue's rows (techniques/pipeline/face_rows.h)
  bool operator()(const Fragment&) const { return true; }
  void finish_tile(int x0, int y0, int x1, int y1, float* out, size_t stride) const {
    // Plane coordinates (u, v) of the texel centres (x + 0.5, y + 0.5).
    const float du = (face->right_edge - face->left) / float(face->width);
    const float dv = (face->top - face->bottom) / float(face->height);
    if (!min_bits) {
      for (int y = y0; y < y1; ++y) {
        float* const row = out + size_t(y) * stride;
        if (face->paraboloid)
          rows->paraboloid_row(row, x0, x1, inv_far);
        else
          rows->radial_row(row, x0, x1, face->left, du, face->top - (float(y) + 0.5f) * dv,
                           inv_far);
      }
      return;
    }
    // With the conversion: the stored distances' minimum (ESM's shift).
    float m = std::numeric_limits<float>::infinity();
    if (!face->paraboloid) {
      m = rows->radial_tile_min(out, stride, x0, x1, y0, y1, face->left, du, face->top, dv,
                                inv_far);
    } else {
      for (int y = y0; y < y1; ++y) {
        const float rm = rows->paraboloid_row_min(out + size_t(y) * stride, x0, x1, inv_far);
        m = rm < m ? rm : m;
      }
    }
    atomic_min_float(*min_bits, m);
  }
};

// World → clip of a face. A cube face without a guard band uses the cube's own 90° projection
// (techniques/pipeline/cube_faces.h), the matrices csm has always rendered with; every other face its
// frustum from the plane extent (the two agree up to float rounding).
mat4 face_matrix(const FaceLayout& layout, size_t i, const PointLight& light) {
  if (layout.kind == FaceLayoutKind::Cube && layout.guard == 0)
    return cube_face_projection(light) * cube_face_view(light, int(i));
  return face_view_proj(layout.faces[i], light);
}

// The paraboloid projection of a face from the light.
ParaboloidProjection face_paraboloid(const LightFace& f, const PointLight& light) {
  ParaboloidProjection p;
  p.centre = light.position;
  p.right = f.right;
  p.up = f.up;
  p.forward = f.forward;
  p.left = f.left;
  p.right_edge = f.right_edge;
  p.bottom = f.bottom;
  p.top = f.top;
  return p;
}

}  // namespace

void render_face_distances(const Scene& scene, const FaceLayout& layout,
                           const std::vector<bool>& needed, FaceDistances& out, CullMode cull,
                           int tess, bool min_distance) {
  const size_t n = layout.faces.size();
  out.distance.resize(n);
  out.rendered.assign(n, false);
  const std::vector<MeshView> meshes = scene_mesh_views(scene);
  const AlphaScene alpha = scene_alpha(scene);  // leaves (Krave) cast cut-out shadows
  // The faces are independent. For scenes of moderate size they render concurrently (each
  // face's binning and tiles are parallel loops of their own, so the scheduler balances faces
  // of unequal cost: room100k cube 19.1 -> 17.2 ms at 2 threads). With ~1M triangles the binned
  // frames alive at once cost more in cache and memory traffic than the balance gains
  // (room1m 93 -> 106 ms), so those render one face after the other. Stats are summed in face
  // order; no output depends on the schedule.
  constexpr size_t kConcurrentFacesMaxTriangles = 250000;
  const bool concurrent = scene.triangle_count() <= kConcurrentFacesMaxTriangles;
  std::vector<RasterStats> stats(n);
  std::vector<std::atomic<uint32_t>> min_bits(n);
  for (auto& b : min_bits) b.store(std::bit_cast<uint32_t>(std::numeric_limits<float>::infinity()));
  // Storage is sized here, on the calling thread, face after face: the faces then come from
  // one malloc arena, near each other, so the lookup kernels can gather from all of them with
  // 32-bit offsets from one base (techniques/lookup/map_lookup_simd.h). Sized by worker threads they
  // would land in per-thread arenas gigabytes apart.
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i])
      out.distance[i].clear();
    else
      out.distance[i].resize(layout.faces[i].texel_count());
  }
  auto render_face = [&](size_t i) {
    if (!needed[i]) return;
    const LightFace& face = layout.faces[i];
    // Rasterize straight into the face's storage and convert 1/w to radial distance in place
    // (tile epilogue): one buffer per face.
    DepthTarget target;
    target.inv_w.swap(out.distance[i]);
    target.resize(face.width, face.height);
    FaceRadialShader shader{&face, 1.0f / scene.light.far,
                            min_distance ? &min_bits[i] : nullptr,
                            &face_row_kernels(process_isa())};
    if (face.paraboloid) {
      const ParaboloidProjection pp = face_paraboloid(face, scene.light);
      if (tess > 0) {
        // Opaque meshes only: an alpha-tested mesh's uvs follow its own triangles.
        std::vector<Tessellated> pieces(meshes.size());
        std::vector<MeshView> views = meshes;
        const float per_unit = float(face.width) / (face.right_edge - face.left);
        for (size_t m = 0; m < meshes.size(); ++m) {
          if (meshes[m].skip || (alpha.any && alpha.meshes[m].texture)) continue;
          tessellate(meshes[m], pp, per_unit, float(tess), pieces[m]);
          views[m].positions = pieces[m].positions.data();
          views[m].vertex_count = pieces[m].positions.size();
          views[m].indices = pieces[m].indices.data();
          views[m].triangle_count = pieces[m].indices.size() / 3;
          views[m].has_bounds = false;
        }
        // The alpha shader finds a triangle's mesh by the running triangle count.
        AlphaScene tess_alpha = alpha;
        for (size_t m = 0; m < views.size() && m + 1 < tess_alpha.first_triangle.size(); ++m)
          tess_alpha.first_triangle[m + 1] = tess_alpha.first_triangle[m] + uint32_t(views[m].triangle_count);
        stats[i] = rasterize_alpha(views, tess_alpha, mat4(1.0f), cull, face.width, face.height,
                                   target, shader, &pp);
      } else {
        stats[i] = rasterize_alpha(meshes, alpha, mat4(1.0f), cull, face.width, face.height,
                                   target, shader, &pp);
      }
    } else {
      stats[i] = rasterize_alpha(meshes, alpha, face_matrix(layout, i, scene.light), cull,
                                 face.width, face.height, target, shader);
    }
    target.inv_w.swap(out.distance[i]);
  };
  if (concurrent)
    parallel_for(0, n, render_face);
  else
    for (size_t i = 0; i < n; ++i) render_face(i);
  out.triangles_submitted = out.triangles_culled = out.triangles_binned = out.texels_rendered = 0;
  if (min_distance)
    out.min_distance.assign(n, std::numeric_limits<float>::infinity());
  else
    out.min_distance.clear();
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) continue;
    if (min_distance) out.min_distance[i] = std::bit_cast<float>(min_bits[i].load());
    out.rendered[i] = true;
    out.triangles_submitted += stats[i].triangles_in;
    out.triangles_culled += stats[i].culled_frustum;
    out.triangles_binned += stats[i].setups;
    out.texels_rendered += layout.faces[i].texel_count();
  }
}

}  // namespace shadowlab
