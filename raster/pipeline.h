#pragma once
// The whole rasterizer in one call: transform → clip → setup → bin → per-tile raster.
#include <vector>

#include "core/scene.h"
#include "raster/rasterize_tile.h"
#include "raster/tile_binner.h"

namespace shadowlab {

// Mesh views of every mesh of the scene, in order (global triangle index runs over them).
std::vector<MeshView> scene_mesh_views(const Scene& scene);
// Maps a global triangle index back to (mesh, triangle within mesh): first_triangle has one
// entry per mesh plus the total.
std::vector<uint32_t> scene_first_triangles(const Scene& scene);

// Renders `meshes` with `view_proj` (or `paraboloid`: raster/paraboloid.h) into `depth` (resized to width × height; every pixel is
// cleared to 0 before the first triangle touches it).
template <class Shader>
RasterStats rasterize(const std::vector<MeshView>& meshes, const mat4& view_proj, CullMode cull,
                      int width, int height, DepthTarget& depth, Shader& shader,
                      const ParaboloidProjection* paraboloid = nullptr) {
  depth.resize(width, height);
  const BinnedFrame frame = bin_triangles(meshes, view_proj, cull, width, height, paraboloid);
  rasterize_frame(frame, depth, shader);
  return frame.stats;
}

// A shader that keeps every fragment and computes no attributes: the depth-only fast path.
struct DepthOnlyShader {
  static constexpr bool kNeedsAttributes = false;
  static constexpr bool kKeepsAll = true;
  bool operator()(const Fragment&) const { return true; }
};

}  // namespace shadowlab
