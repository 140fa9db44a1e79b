#include "techniques/pipeline/light_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/timer.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {

FaceLayout map_layout(const MapParams& p, const Scene& scene) {
  const int guard = map_guard(p);
  switch (p.layout) {
    case FaceLayoutKind::Cube: return cube_layout(p.res, guard);
    case FaceLayoutKind::Tetrahedron: return tetra_layout(p.res, guard);
    case FaceLayoutKind::Projector: return projector_layout(scene.projector, p.res, guard);
    case FaceLayoutKind::DualParaboloid: return dual_paraboloid_layout(p.res, guard);
  }
  SL_CHECK(false);
  return {};
}

void render_light_map(const Scene& scene, const MapParams& p, const std::vector<bool>& needed,
                      LightMap& map) {
  render_face_distances(scene, map.layout, needed, map.dist, CullMode::None, p.tess,
                        map_filter_ops(p.filter).wants_min_distance);
  if (p.depth == DepthFormat::F32) return;
  for (size_t f = 0; f < map.dist.distance.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    LineAlignedFloats& d = map.dist.distance[f];
    quantize_depths(d.data(), d.size(), p.depth);
    if (map.dist.min_distance.empty()) continue;
    // The stored values' minimum again (the render's was of the unquantized distances), per
    // chunk in parallel, then over the chunks in order (min is exact: any order gives it).
    const size_t grain = 65536, chunks = (d.size() + grain - 1) / grain;
    std::vector<float> part(chunks, std::numeric_limits<float>::infinity());
    parallel_for_chunks(d.size(), grain, [&](size_t b, size_t e) {
      float m = std::numeric_limits<float>::infinity();
      for (size_t i = b; i < e; ++i) m = d[i] < m ? d[i] : m;
      part[b / grain] = m;
    });
    float m = std::numeric_limits<float>::infinity();
    for (const float v : part) m = v < m ? v : m;
    map.dist.min_distance[f] = m;
  }
}

void filter_light_map(const MapParams& p, LightMap& map) {
  const size_t nf = map.layout.faces.size();
  map.a.resize(nf);
  map.max_depth.resize(nf);
  map_filter_ops(p.filter).filter(p, map);
}

void lookup_light_map(const Scene& scene, const GBuffer& g, const MapParams& p,
                      const LightMap& map, ImageF& mask, ImageU32* texels) {
  map_filter_ops(p.filter).lookup(scene, g, p, map, mask, texels);
}

const std::vector<const MapFilterOps*>& map_filters() {
  // The rows of techniques/filters/all.h, in its order.
  static const std::vector<const MapFilterOps*> rows = {
#define SHADOWLAB_FILTER(id, ops) &ops,
#define SHADOWLAB_FILTER_KEYS(type, member)
#include "techniques/filters/all.h"
#undef SHADOWLAB_FILTER
#undef SHADOWLAB_FILTER_KEYS
  };
  return rows;
}

const MapFilterOps& map_filter_ops(MapFilter id) {
  for (const MapFilterOps* f : map_filters())
    if (f->id == id) return *f;
  SL_CHECK(false);
  return *map_filters().front();
}

namespace {

// Work of one repeat (docs/metric.md): texels a lookup reads and the bytes per texel.
void count_work(const MapParams& p, const LightMap& map, size_t looked_up, WorkCounts& w) {
  uint64_t filtered_texels = 0;  // texels of the rendered faces the filter wrote
  for (size_t f = 0; f < map.layout.faces.size(); ++f)
    if (map.dist.rendered[f])
      filtered_texels += tile_texels(face_tiles(map, f), map.layout.faces[f].width,
                                     map.layout.faces[f].height);
  w.triangles_submitted = map.dist.triangles_submitted;
  w.triangles_binned = map.dist.triangles_binned;
  w.texels_rendered = map.dist.texels_rendered;
  w.pixels_looked_up = looked_up;
  const MapFilterOps& f = map_filter_ops(p.filter);
  const uint64_t planes = f.stored_planes(p);
  const uint64_t tap_bytes = f.tap_bytes(p);
  const uint64_t taps_per_lookup = f.taps_per_lookup(p);
  w.texels_filtered = planes * filtered_texels;
  w.taps = taps_per_lookup * looked_up;
  w.bytes_written = 4 * (map.dist.texels_rendered + w.texels_filtered);
  w.bytes_read = tap_bytes * w.taps;
}

}  // namespace

namespace {

// Texels of every face of a layout, guard bands included.
uint64_t layout_texels(const FaceLayout& layout) {
  uint64_t texels = 0;
  for (const LightFace& f : layout.faces) texels += f.texel_count();
  return texels;
}

}  // namespace

uint64_t light_map_bytes(const MapParams& p, const Scene& scene) {
  const uint64_t planes = map_filter_ops(p.filter).stored_planes(p);
  return layout_texels(map_layout(p, scene)) * 4 * (1 + planes);
}

bool light_map_needs_progress(const MapParams& p, const FaceLayout& layout) {
  const uint64_t texels = layout_texels(layout);
  // A pass per texel, times the box width for the filters that blur (blur is 0 where no key
  // declares it).
  const uint64_t units = texels * uint64_t(std::max(p.blur, 1));
  return units > 1000000000ull;  // ~2 s at ~2 ns per unit
}

ShadowResult run_light_map(const MapParams& p, const Scene& scene, const GBuffer& gbuffer,
                           const RunOptions& options) {
  if (p.layout == FaceLayoutKind::Projector && !scene.projector.enabled)
    throw InputError(options.flag, "the projector layout needs a slide projector light (--slide)");
  LightMap map;
  map.layout = map_layout(p, scene);
  ShadowResult r;
  r.faces_total = int(map.layout.faces.size());
  std::vector<bool> needed;
  size_t looked_up = 0;
  std::vector<double> faces_t, render_t, filter_t, map_t, lookup_t;
  const int repeats = std::max(1, options.repeats);
  // Stage 2 also finds the tiles the lookups read when the filter filters only those.
  const MapFilterOps& ops = map_filter_ops(p.filter);
  const bool by_tiles = ops.by_tiles && ops.by_tiles(p);
  // Long builds show a progress line (stderr terminal only; it touches no result).
  ProgressLine progress("light map", size_t(repeats) * 3,
                        options.progress && light_map_needs_progress(p, map.layout));
  for (int rep = 0; rep < repeats; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    needed = faces_needed(scene, gbuffer, map.layout, p);
    faces_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    render_light_map(scene, p, needed, map);
    render_t.push_back(ms_since(t0));
    progress.advance();
    t0 = std::chrono::steady_clock::now();
    // The tiles the lookups read are the filter's to find (stage 2's second answer, only the
    // filter uses it), so their time counts as the filter's.
    if (by_tiles) map.tiles = texel_tiles_needed(scene, gbuffer, map.layout, p, needed);
    filter_light_map(p, map);
    filter_t.push_back(ms_since(t0));
    progress.advance();
    map_t.push_back(faces_t.back() + render_t.back() + filter_t.back());
    t0 = std::chrono::steady_clock::now();
    lookup_light_map(scene, gbuffer, p, map, r.mask, options.want_texels ? &r.texels : nullptr);
    lookup_t.push_back(ms_since(t0));
    progress.advance();
  }
  // The looked-up pixel count (a work count, not part of the technique) by a full pass outside
  // the timings: the timed stage may stop early once every face is known to be needed.
  faces_needed(scene, gbuffer, map.layout, p, &looked_up);
  r.faces_ms = median(faces_t);
  r.render_ms = median(render_t);
  r.filter_ms = median(filter_t);
  r.map_ms = median(map_t);
  r.lookup_ms = median(lookup_t);
  count_work(p, map, looked_up, r.work);
  for (bool n : needed) r.faces_needed += n ? 1 : 0;
  r.faces_rendered = r.faces_needed;
  r.triangles_culled = map.dist.triangles_culled;
  const LightFace& f0 = map.layout.faces[0];
  r.notes = "faces " + std::to_string(r.faces_rendered) + "/" + std::to_string(r.faces_total) +
            " rendered (" + std::to_string(f0.width) + "x" + std::to_string(f0.height) +
            " texels each, guard " + std::to_string(map.layout.guard) + "), " +
            std::to_string(r.triangles_culled) + " of " +
            std::to_string(r.work.triangles_submitted) +
            " triangle submissions culled before binning";
  return r;
}

}  // namespace shadowlab
