#pragma once
// Stage 2 of the light-map pipeline, its second answer (techniques/pipeline/light_map.h): which tiles of
// 32 × 32 texels of each face some pixel's bilinear lookup reads, so that a filter (stage 5)
// transforms and blurs only those tiles, the rest of the face being read by no lookup. The
// tiles are a superset of the exact ones, never a subset: a tile missing would leave a lookup
// reading a value the filter did not write, so the masks would change (tests/techniques/
// texel_tiles_test.cpp checks both against every pixel's own bilinear footprint). See
// docs/techniques/pipeline.md.
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/pipeline/map_params.h"

namespace shadowlab {

constexpr int kTexelTile = 32;  // tile edge, texels; also the filters' band of rows

// The tiles of one face's image some lookup reads: need[ty · tiles_x + tx] != 0 for the tile of
// texels [32·tx, 32·tx + 32) × [32·ty, 32·ty + 32) (clipped to the image). An empty `need`
// means every tile.
struct FaceTiles {
  int tiles_x = 0, tiles_y = 0;
  std::vector<uint8_t> need;
  bool every() const { return need.empty(); }
};

// Texel columns [x0, x1) of one band of rows.
struct TexelSpan {
  int x0, x1;
};

// The runs of needed tiles in tile row `band` of a face w texels wide, as texel spans clipped to
// w, left to right (tiles nullptr or every(): the whole row).
void tile_spans(const FaceTiles* tiles, int band, int w, std::vector<TexelSpan>& spans);

// Texels of a w × h face inside its needed tiles (every texel for nullptr or every()).
uint64_t tile_texels(const FaceTiles* tiles, int w, int h);

// Per face of the layout, the tiles read by the bilinear lookups (2 × 2 texels around the
// receiver's texel coordinates, techniques/lookup/map_receiver.h's bilinear_taps) of the covered,
// light-facing pixels; faces not in `faces` get no tiles. Pixels are decided a GBuffer block at
// a time where the block's bounds lie in one face (box_single_face, or in front of the
// projector): the perspective image of a box is the convex hull of its corners' images, so the
// corners' texel coordinates bound every pixel's, and a margin of one texel covers float
// rounding. The other blocks' pixels are each looked at (their receivers, as the lookup computes
// them). The dual-paraboloid map is not gnomonic: there a block's box is bounded by its
// circumscribed sphere, whose cap of directions the map takes to a disk (texel_tiles.cpp).
std::vector<FaceTiles> texel_tiles_needed(const Scene& scene, const GBuffer& g,
                                          const FaceLayout& layout, const MapParams& p,
                                          const std::vector<bool>& faces);

// The same tiles from every pixel's own receiver, no block decided: the test's oracle.
std::vector<FaceTiles> texel_tiles_needed_by_pixels(const Scene& scene, const GBuffer& g,
                                                    const FaceLayout& layout, const MapParams& p,
                                                    const std::vector<bool>& faces);

}  // namespace shadowlab
