#include "techniques/face_render.h"

#include <cmath>

#include "core/parallel.h"
#include "raster/alpha_test.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

// Depth-only shader whose tile epilogue turns 1/w (reciprocal view depth) into normalised
// radial distance: the ray through a texel centre with plane coordinates (u, v) has view
// direction (u, v, -1), so |p - L| = view depth × sqrt(1 + u² + v²). An empty texel (1/w = 0)
// divides to +inf, "nothing seen".
struct FaceRadialShader {
  static constexpr bool kNeedsAttributes = false;
  static constexpr bool kKeepsAll = true;
  const LightFace* face;
  float inv_far;
  float* out;  // the target's own 1/w storage: each texel is read, then overwritten
  bool operator()(const Fragment&) const { return true; }
  void finish_tile(int x0, int y0, int x1, int y1, const DepthTarget& depth) const {
    // Plane coordinates (u, v) of the texel centres (x + 0.5, y + 0.5).
    const float du = (face->right_edge - face->left) / float(face->width);
    const float dv = (face->top - face->bottom) / float(face->height);
    for (int y = y0; y < y1; ++y) {
      float* row = out + size_t(y) * size_t(depth.width);
      const float v = face->top - (float(y) + 0.5f) * dv;
      const float vv = 1.0f + v * v;
      for (int x = x0; x < x1; ++x) {
        const float u = face->left + (float(x) + 0.5f) * du;
        row[x] = std::sqrt(vv + u * u) * inv_far / row[x];
      }
    }
  }
};

}  // namespace

void render_face_distances(const Scene& scene, const FaceLayout& layout,
                           const std::vector<bool>& needed, FaceDistances& out) {
  const size_t n = layout.faces.size();
  out.distance.resize(n);
  out.rendered.assign(n, false);
  out.triangles_submitted = out.triangles_culled = 0;
  const std::vector<MeshView> meshes = scene_mesh_views(scene);
  const AlphaScene alpha = scene_alpha(scene);  // leaves (Krave) cast cut-out shadows
  // Faces one after the other; each face's binning and tiles are parallel loops.
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) {
      out.distance[i].clear();
      continue;
    }
    const LightFace& face = layout.faces[i];
    DepthTarget target;
    target.inv_w.swap(out.distance[i]);
    target.resize(face.width, face.height);
    FaceRadialShader shader{&face, 1.0f / scene.light.far, target.inv_w.data()};
    const RasterStats st = rasterize_alpha(meshes, alpha, face_view_proj(face, scene.light),
                                           CullMode::None, face.width, face.height, target, shader);
    target.inv_w.swap(out.distance[i]);
    out.rendered[i] = true;
    out.triangles_submitted += st.triangles_in;
    out.triangles_culled += st.culled_frustum;
  }
}

}  // namespace shadowlab
