#pragma once
// The light-map pipeline: every shadow-map technique (csm, tsm, psm, the VSM and ESM families;
// a layout × a filter, techniques/pipeline/map_params.h) runs through the same stages, each timed:
//   1. layout       face frusta, face of a direction, texel mapping, guard band (light_faces.h)
//   2. faces        which faces some pixel's lookup touches; neighbours only for pixels whose
//                   PCF footprint reaches past their face's edge (SeamMode::Cross)
//   3. render       one radial-distance renderer for every layout (face_render.h)
//   4. store        quantize (depth=) and the filter's own transform (moments, exponentials)
//   5. filter       separable box blur (moment_filter.h)
//   6. lookup       compare or reconstruct, with the bias modes (map_receiver.h), through the
//                   SIMD kernels where they exist (their scalar loops are the oracle)
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "techniques/pipeline/face_render.h"
#include "techniques/pipeline/faces_needed.h"
#include "techniques/pipeline/map_params.h"
#include "techniques/filters/moments_common/moment_filter.h"
#include "techniques/registry/technique.h"
#include "techniques/pipeline/texel_tiles.h"

namespace shadowlab {

// A built map: the layout, the rendered distances and, for filtering techniques, the filtered
// values per face, interleaved per texel in plane a so that one load fetches all of a tap's
// values (docs/performance_history.md): VSM: mean, variance (or m1, m2 in fp32 mode), texel i's
// at a[2i], a[2i + 1], and the max depth in its own plane when maxdepth_eps > 0; ESM: the
// log-space occluder term c·z, a[i]; EVSM: the positive warp's mean and variance, then with 4
// moments the negative warp's, a[S·i + 0..S−1] with S = 2 or 4; MSM: E[d]…E[d⁴], a[4i + 0..3].
struct LightMap {
  FaceLayout layout;
  FaceDistances dist;
  std::vector<std::vector<float>> a, max_depth;
  // Stage 2's tiles per face for a filter that filters by tiles (MapFilterOps::by_tiles); empty:
  // every texel is filtered.
  std::vector<FaceTiles> tiles;
  FilterScratch scratch;  // the max filter's, reused by every face and every rebuild
};

// Face f's tiles for the filter, or nullptr for every texel.
inline const FaceTiles* face_tiles(const LightMap& map, size_t f) {
  return map.tiles.empty() ? nullptr : &map.tiles[f];
}

// The layout of a technique's params (the projector's needs scene.projector).
FaceLayout map_layout(const MapParams& p, const Scene& scene);
// Renders the needed faces and stores them (quantized).
void render_light_map(const Scene& scene, const MapParams& p, const std::vector<bool>& needed,
                      LightMap& map);
// Filters a rendered map (moment maps only; a no-op for depth compare).
void filter_light_map(const MapParams& p, LightMap& map);
// Looks every GBuffer pixel up in a built map.
void lookup_light_map(const Scene& scene, const GBuffer& g, const MapParams& p,
                      const LightMap& map, ImageF& mask, ImageU32* texels);

// Bytes the map of these params holds at once: every face's stored distances (4 B per texel)
// and the filter's planes (4 B each per texel); faces are counted as if all were needed.
uint64_t light_map_bytes(const MapParams& p, const Scene& scene);

// True when building this map is expected to take over ~2 s on the machines we measure on
// (work units: texels, times the blur width for the filters; ~2 ns each), so the pipeline shows
// a progress line (when RunOptions::progress, i.e. stderr is a terminal).
bool light_map_needs_progress(const MapParams& p, const FaceLayout& layout);

// The whole pipeline with per-phase timings (medians of options.repeats) and work counts.
ShadowResult run_light_map(const MapParams& p, const Scene& scene, const GBuffer& gbuffer,
                           const RunOptions& options);

}  // namespace shadowlab
