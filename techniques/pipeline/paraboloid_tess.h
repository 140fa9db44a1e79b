#pragma once
// Edge splitting for the dual-paraboloid layout (tess=N; techniques/pipeline/face_render.cpp): the
// paraboloid map is applied per vertex and the rasterizer interpolates linearly, so long edges
// are split in world space before projection until their images are short.
#include <cstdint>
#include <vector>

#include "raster/paraboloid.h"
#include "raster/tile_binner.h"

namespace shadowlab {

// A triangle soup: 3 positions per triangle, indices 0, 1, 2, …
struct Tessellated {
  std::vector<vec3> positions;
  std::vector<uint32_t> indices;
};

// Splits every edge of `m` whose image under `pp` is longer than max_texels texels
// (texels_per_unit: texels per image-plane unit) at its world-space midpoint, recursively; the
// pieces keep their triangle's winding and submission order.
void tessellate(const MeshView& m, const ParaboloidProjection& pp, float texels_per_unit,
                float max_texels, Tessellated& out);

}  // namespace shadowlab
