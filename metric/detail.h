#pragma once
// Shadow detail (docs/design.md §5.6): how many screen pixels share one shadow-map texel.
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace shadowlab {

// Share ratio S: over the pixels whose texel index is not kNoTexel, the RMS of the number of
// pixels sharing that pixel's index (one value per pixel), i.e. √(Σ_t n_t³ / Σ_t n_t) over the
// texels t with n_t pixels. 0 when no pixel has a texel. Counts come from a radix sort, so the
// result is deterministic.
double texel_share_ratio(const ImageU32& texels);

// Buffers of the texel sort, reusable across calls.
struct DetailScratch {
  std::vector<uint32_t> keys, swap;
};
double texel_share_ratio(const ImageU32& texels, DetailScratch& scratch);

// Detail score 1/S; 1 when `texels` is null (no shadow map, e.g. ray tracing) or no pixel has a
// texel.
double detail_score(const ImageU32* texels);
double detail_score(const ImageU32* texels, DetailScratch& scratch);

}  // namespace shadowlab
