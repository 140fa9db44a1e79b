#pragma once
// Front end of the rasterizer: vertex transform, trivial rejection, clipping, setup and binning
// of triangles to kTileSize² tiles. Triangles are processed in fixed chunks of submission order
// (in parallel); each chunk keeps its own per-tile lists (count, prefix-sum, fill), and tiles
// visit the chunks in order, so every tile sees its triangles in submission order whatever the
// thread count.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/math.h"
#include "raster/raster_types.h"
#include "raster/paraboloid.h"
#include "raster/setup.h"

namespace shadowlab {

// A mesh as the rasterizer sees it: world-space positions and a triangle list, and optionally
// its bounds, which let a whole mesh outside the view frustum be culled before any vertex work.
struct MeshView {
  const vec3* positions = nullptr;
  size_t vertex_count = 0;
  const uint32_t* indices = nullptr;  // 3 per triangle
  size_t triangle_count = 0;
  bool has_bounds = false;
  vec3 lo{0.0f}, hi{0.0f};            // world-space AABB of the positions (when has_bounds)
  bool skip = false;                  // not drawn in this pass (its triangles still count in the
                                      // global triangle index; not counted in the stats)
};

// True when the box [lo, hi] lies entirely outside one plane of the frustum of view_proj
// (left, right, bottom, top or near). Conservative: false means "may be visible".
bool box_outside_frustum(const vec3& lo, const vec3& hi, const mat4& view_proj);

// An allocator whose value-initialization is default-initialization: resize() leaves new
// setups unwritten, so the 8-triangle setup writes its records in place (every field) instead
// of through a staging copy (a memmove of 1.4 KB per batch was 3 % of room1m's cube).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Triangles of one chunk that touch one tile are setups[chunk][items[offsets[t] .. offsets[t+1])].
struct BinnedChunk {
  std::vector<TriangleSetup, DefaultInitAllocator<TriangleSetup>> setups;
  std::vector<uint32_t> offsets;  // tiles + 1 entries
  std::vector<uint32_t> items;    // indices into setups
};

struct BinnedFrame {
  int width = 0, height = 0;
  int tiles_x = 0, tiles_y = 0;
  std::vector<BinnedChunk> chunks;
  RasterStats stats;
};

// Transforms, clips, sets up and bins every triangle of `meshes` (global triangle index =
// running count over the meshes in order) for a width × height viewport. With `paraboloid`,
// vertices go through that projection instead of view_proj (raster/paraboloid.h; no
// whole-mesh culling then).
BinnedFrame bin_triangles(const std::vector<MeshView>& meshes, const mat4& view_proj,
                          CullMode cull, int width, int height,
                          const ParaboloidProjection* paraboloid = nullptr);

}  // namespace shadowlab
