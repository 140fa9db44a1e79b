#pragma once
// A filter of the light-map pipeline (techniques/pipeline/light_map.h): what a technique adds to
// a layout. Each filter is a folder under techniques/filters/ whose sources define its row below:
// its own keys, its store + blur stage and its lookup; techniques/filters/all.h lists the
// folders, one line each, and the declarations below, MapFilter, MapParams' keys members and
// map_filters() all follow from that list. The registry (techniques/registry/technique.cpp)
// combines every layout with every row of map_filters(), so a new filter is its folder and its
// line in the list (docs/extending.md).
#include <cstdint>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/scene.h"
#include "techniques/pipeline/map_params.h"
#include "techniques/registry/technique_spec.h"

namespace shadowlab {

struct LightMap;

struct MapFilterOps {
  const char* suffix;  // the technique name's filter part: c + "vsm" = cvsm
  const char* what;    // one line for --list-techniques
  MapFilter id;
  // The filter's own keys in reading order (techniques/registry/technique_keys.h); map_keys puts the
  // shared and the layout's keys before them.
  const std::vector<MapKey>& (*keys)();
  // Stages 4–5: the filter's transform and blur of the rendered faces into map.a/max_depth
  // (only map.tiles' tiles when by_tiles says so and map.tiles is not empty).
  void (*filter)(const MapParams& p, LightMap& map);
  // Stage 6: every GBuffer pixel's visibility (and texel index when texels is given).
  void (*lookup)(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
                 ImageF& mask, ImageU32* texels);
  // Work counts (WorkCounts, techniques/registry/technique.h): map texels one lookup reads, the bytes per such tap,
  // and the float planes the filter stores per texel.
  uint64_t (*taps_per_lookup)(const MapParams& p);
  uint64_t (*tap_bytes)(const MapParams& p);
  uint64_t (*stored_planes)(const MapParams& p);
  // True when the filter (stage 5) transforms and blurs only the tiles stage 2 found read by some
  // lookup (map.tiles, techniques/pipeline/texel_tiles.h) under these params; nullptr: never (no filter,
  // or one that reads the whole face).
  bool (*by_tiles)(const MapParams& p);  // map_filter_always_by_tiles for every setting
  // True when the filter reads FaceDistances::min_distance, which the render then finds.
  bool wants_min_distance;
};

// Every filter's row (sm: kDepthCompare, vsm: kVarianceMap, …), defined in its folder.
#define SHADOWLAB_FILTER(id, ops) extern const MapFilterOps ops;
#define SHADOWLAB_FILTER_KEYS(type, member)
#include "techniques/filters/all.h"
#undef SHADOWLAB_FILTER
#undef SHADOWLAB_FILTER_KEYS

// MapFilterOps::by_tiles of a filter that goes by tiles under any params.
inline bool map_filter_always_by_tiles(const MapParams&) { return true; }

// Every filter, in registry order.
const std::vector<const MapFilterOps*>& map_filters();
// The row of a filter id.
const MapFilterOps& map_filter_ops(MapFilter id);

}  // namespace shadowlab
