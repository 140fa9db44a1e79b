#pragma once
// The face-map techniques (tsm, cvsm, tvsm, cesm, tesm; parameters in face_map_params.h):
// render the needed faces of a cube or tetrahedral layout with guard bands, filter them when the
// technique filters (VSM moments, ESM log-space exponentials), and look every GBuffer pixel up.
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "techniques/face_map_params.h"
#include "techniques/face_render.h"
#include "techniques/moment_filter.h"
#include "techniques/technique.h"

namespace shadowlab {

// A built map: the layout, the rendered distances and, for filtering techniques, the filtered
// planes per face (VSM: mean + variance, or m1 + m2 in fp32 mode, and the max depth when
// maxdepth_eps > 0; ESM: the log-space occluder term c·z in plane a).
struct FaceMap {
  FaceLayout layout;
  FaceDistances dist;
  std::vector<std::vector<float>> a, b, max_depth;
  FilterScratch scratch;  // reused by every face and every rebuild
};

// Builds the map for the given needed faces.
void build_face_map(const Scene& scene, const FaceMapParams& p, const std::vector<bool>& needed,
                    FaceMap& map);
// Looks every GBuffer pixel up in a built map.
void lookup_face_map(const Scene& scene, const GBuffer& g, const FaceMapParams& p,
                     const FaceMap& map, ImageF& mask, ImageU32* texels);

ShadowResult run_face_map_technique(const TechniqueSpec& spec, const Scene& scene,
                                    const GBuffer& gbuffer, const RunOptions& options);

}  // namespace shadowlab
