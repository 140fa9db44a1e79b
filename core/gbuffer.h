#pragma once
// GBuffer: what the camera pass leaves per pixel, the common input of every technique and of
// the Embree reference (both evaluate visibility at these same surface points).
#include <cstdint>
#include <limits>
#include <vector>

#include "core/math.h"

namespace shadowlab {

constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

// Bounds of the covered pixels' positions in one kGBufferBlock × kGBufferBlock block of the image
// (world space, metres); lo > hi when the block has no covered pixel, ±inf when a position is
// not finite. A hierarchy over the positions, like a depth pyramid: the light-map pipeline's
// faces-needed stage decides whole blocks from them (techniques/pipeline/faces_needed.h).
constexpr int kGBufferBlock = 16;
struct BlockBounds {
  vec3 lo{std::numeric_limits<float>::infinity()};
  vec3 hi{-std::numeric_limits<float>::infinity()};
  bool empty() const { return !(lo.x <= hi.x); }
};

struct GBuffer {
  int width = 0;
  int height = 0;
  // Per pixel, row-major (index y * width + x). Valid only where covered != 0.
  std::vector<vec3> position;        // world space, metres (interpolated, perspective-correct)
  // The shading attributes, optional: the camera pass leaves them empty (size 0), since only
  // the pictures for people read them; shading_attributes (core/gbuffer_shading.h) gives a
  // pixel's from its triangle where they are absent. Writers of other GBuffers may fill them.
  std::vector<vec3> normal;          // shading normal, world space, unit length
  std::vector<vec2> uv;              // texture coordinates (0 when the mesh has none)
  std::vector<vec3> geo_normal;      // geometric normal of the triangle, world space, unit,
                                     // facing the eye (two-sided)
  std::vector<float> depth;          // view-space distance along -z, metres (+inf where empty)
  std::vector<uint32_t> mesh_id;     // index into Scene::meshes, kNoPrimitive where empty
  std::vector<uint32_t> prim_id;     // triangle index within that mesh, kNoPrimitive where empty
  std::vector<uint8_t> covered;      // 1 where some triangle covers the pixel centre
  // Per block, row-major over ceil(width / 16) × ceil(height / 16) blocks: left by the camera
  // pass (render_gbuffer); empty for GBuffers written by other code, which then get no
  // block-level shortcuts. resize and reshape clear it: a writer that changes positions after
  // the camera pass must call compute_block_bounds (core/block_bounds.h) again.
  std::vector<BlockBounds> block_bounds;

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  int blocks_x() const { return (width + kGBufferBlock - 1) / kGBufferBlock; }
  int blocks_y() const { return (height + kGBufferBlock - 1) / kGBufferBlock; }
  bool has_block_bounds() const {
    return block_bounds.size() == size_t(blocks_x()) * size_t(blocks_y());
  }
  // Sizes every array and resets it to the empty values (covered 0, ids kNoPrimitive, ...).
  void resize(int w, int h);
  // Sizes every array but the shading attributes, which it empties, keeping whatever values
  // are there (for the camera pass, which sets every pixel).
  void reshape(int w, int h);
  bool has_shading_attributes() const {
    return normal.size() == pixel_count() && uv.size() == pixel_count();
  }
};

}  // namespace shadowlab
