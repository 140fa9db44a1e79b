#pragma once
// Renders the faces of a layout (techniques/pipeline/light_faces.h) as depth-only passes and stores, per
// texel, the radial distance from the light to the nearest surface through the texel centre,
// normalised by the light range: |p - L| / far (+inf where the texel saw nothing). One renderer
// for every layout and technique (the pipeline's stage 3, techniques/pipeline/light_map.h).
#include <vector>

#include "core/aligned_vector.h"
#include "core/scene.h"
#include "raster/raster_types.h"
#include "techniques/pipeline/light_faces.h"

namespace shadowlab {

struct FaceDistances {
  // Per face: texel_count() values, or empty if not rendered; 64-byte aligned (the rasterizer
  // streams whole lines into large faces: raster/rasterize_tile.h).
  std::vector<LineAlignedFloats> distance;
  std::vector<bool> rendered;
  // Per face, when asked for: the smallest stored distance (+inf when it saw nothing, or was not
  // rendered), found in the tile epilogue's conversion loop (the ESM filter's shift). Empty
  // otherwise, and for distances written by other code (the ESM filter then finds it itself).
  std::vector<float> min_distance;
  size_t triangles_submitted = 0;  // summed over rendered faces
  size_t triangles_culled = 0;     // rejected before binning (outside a face's frustum)
  size_t triangles_binned = 0;     // reached binning (after culling and clipping)
  size_t texels_rendered = 0;      // texels of the rendered faces
};

// Renders the faces with needed[i] set. Storage is reused across calls. Faces are rendered
// with no face culling unless `cull` says otherwise (benchmarks). `tess` > 0 (paraboloid faces
// only): triangles whose image has an edge longer than tess texels are split first.
// `min_distance` also fills out.min_distance (it costs the render ~4 % on the default scene, so
// only the filters that use it ask).
void render_face_distances(const Scene& scene, const FaceLayout& layout,
                           const std::vector<bool>& needed, FaceDistances& out,
                           CullMode cull = CullMode::None, int tess = 0,
                           bool min_distance = false);

}  // namespace shadowlab
