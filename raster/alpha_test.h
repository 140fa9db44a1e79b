#pragma once
// Alpha discard (Krave's foliage): a fragment of an alpha-textured material whose alpha at its
// uv is below the material's cutoff is discarded, in the camera pass and in every shadow-map
// pass, with the one lookup and test of core/texture.h that the Embree reference's filters use
// (nearest texel, repeat wrap, uv from barycentric_uv).
//
// Opaque meshes keep the depth-only fast path: rasterize_alpha() draws them first, through the
// SIMD depth kernel with no barycentrics, no uv and no texture fetch, then draws only the
// alpha-textured meshes over the same target with a discarding shader (generic per-pixel path,
// perspective-correct barycentrics). The shader's tile epilogue (finish_tile) runs once, after
// the second pass. Scenes without alpha textures take the single fast pass unchanged.
// Ordering: opaque triangles come before every alpha-tested one; of two fragments at exactly
// equal depth the earlier wins (rasterize_tile.h), so an opaque one wins such a tie.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "core/texture.h"
#include "raster/pipeline.h"

namespace shadowlab {

struct AlphaMesh {
  const ImageF* texture = nullptr;   // RGBA, alpha in channel 3; nullptr = opaque
  const vec2* uvs = nullptr;         // per vertex (an alpha-textured mesh always has them)
  const uint32_t* indices = nullptr;
  float cutoff = 0.5f;
};

// Per scene mesh (same order as scene_mesh_views), with the global triangle ranges.
struct AlphaScene {
  std::vector<AlphaMesh> meshes;
  std::vector<uint32_t> first_triangle;  // scene_first_triangles
  bool any = false;                      // some mesh with triangles is alpha-textured
};

// The scene's alpha data (pointers into `scene`, which must outlive the result).
AlphaScene scene_alpha(const Scene& scene);

// The alpha test of one fragment of global triangle `triangle` with barycentrics `bary`.
inline bool alpha_fragment_passes(const AlphaScene& a, uint32_t triangle, const float bary[3]) {
  // The mesh owning the triangle: few meshes, so a binary search per fragment is cheap.
  const auto it = std::upper_bound(a.first_triangle.begin(), a.first_triangle.end(), triangle);
  const size_t m = size_t(it - a.first_triangle.begin()) - 1;
  const AlphaMesh& am = a.meshes[m];
  if (!am.texture) return true;
  const uint32_t* tri = am.indices + 3 * size_t(triangle - a.first_triangle[m]);
  const vec2 uv = barycentric_uv(am.uvs, tri, bary[1], bary[2]);
  return alpha_test_passes(sample_alpha(*am.texture, uv), am.cutoff);
}

// Wraps a depth-only shader: discards failing alpha fragments, keeps the inner epilogue.
template <class Inner>
struct AlphaDiscardShader {
  static constexpr bool kNeedsAttributes = true;
  static constexpr bool kKeepsAll = false;
  const AlphaScene* alpha;
  Inner* inner;
  bool operator()(const Fragment& f) const {
    return alpha_fragment_passes(*alpha, f.triangle, f.bary) && (*inner)(f);
  }
  void finish_tile(int x0, int y0, int x1, int y1, float* z, size_t stride) const {
    if constexpr (HasFinishTile<Inner>) inner->finish_tile(x0, y0, x1, y1, z, stride);
  }
};

// rasterize() with alpha discard (see the top of this file). `shader` must be a depth-only
// shader (kKeepsAll, no attributes), optionally with a tile epilogue.
template <class Shader>
RasterStats rasterize_alpha(const std::vector<MeshView>& meshes, const AlphaScene& alpha,
                            const mat4& view_proj, CullMode cull, int width, int height,
                            DepthTarget& depth, Shader& shader,
                            const ParaboloidProjection* paraboloid = nullptr) {
  static_assert(kKeepsAll<Shader> && !Shader::kNeedsAttributes);
  if (!alpha.any)
    return rasterize(meshes, view_proj, cull, width, height, depth, shader, paraboloid);
  SL_CHECK_EQ(alpha.meshes.size(), meshes.size());
  std::vector<MeshView> opaque = meshes, cutout = meshes;
  for (size_t m = 0; m < meshes.size(); ++m) (alpha.meshes[m].texture ? opaque : cutout)[m].skip = true;
  depth.resize(width, height);
  DepthOnlyShader plain;
  const BinnedFrame first = bin_triangles(opaque, view_proj, cull, width, height, paraboloid);
  rasterize_frame(first, depth, plain);
  const BinnedFrame second = bin_triangles(cutout, view_proj, cull, width, height, paraboloid);
  AlphaDiscardShader<Shader> discard{&alpha, &shader};
  rasterize_frame(second, depth, discard, /*clear=*/false);
  RasterStats st = first.stats;
  add_stats(st, second.stats);
  return st;
}

}  // namespace shadowlab
