// Every filter of the light-map pipeline, one line each, in registry order (the order of
// --list-techniques, of technique_list() and of every loop over the filters). A filter is its
// folder under techniques/filters/: the header named here declares its keys struct and its row
// (below), its sources define the row (techniques/pipeline/map_filter.h) and its keys.
//
// Each filter header holds, after its guarded declarations, the line
//   SHADOWLAB_FILTER(Id, kOps)                      // MapFilter::Id, the MapFilterOps kOps
//   SHADOWLAB_FILTER_KEYS(KeysStruct, member)       // MapParams::member (none when it has no
//                                                   // keys of its own)
// which this list's includer defines before each reading of it: techniques/pipeline/map_params.h
// (the keys structs, MapFilter, the members of MapParams), techniques/pipeline/map_filter.h (the
// rows' declarations) and techniques/pipeline/light_map.cpp (map_filters()). Hence no include
// guard here. Adding a filter: docs/extending.md.
#include "techniques/filters/sm/sm.h"
#include "techniques/filters/vsm/vsm.h"
#include "techniques/filters/esm/esm.h"
#include "techniques/filters/evsm/evsm.h"
#include "techniques/filters/msm/msm.h"
#include "techniques/filters/pcss/pcss.h"
