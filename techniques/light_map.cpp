#include "techniques/light_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/progress.h"
#include "core/timer.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup_simd.h"
#include "techniques/map_receiver.h"

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

std::vector<bool> faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                               const MapParams& p, size_t* looked_up) {
  const size_t grain = 8192;
  const size_t chunks = (g.pixel_count() + grain - 1) / grain;
  const size_t nf = layout.faces.size();
  const bool projector = layout.kind == FaceLayoutKind::Projector;
  const ProjectorFrame frame = projector ? projector_frame(scene.projector) : ProjectorFrame{};
  // Only cross-face PCF taps can reach another face; with a guard band every tap stays in the
  // receiver's own face image.
  const bool cross = p.filter == MapFilter::Depth && p.seams == SeamMode::Cross && p.pcf > 1;
  // PCSS kernels grow with the penumbra and may reach any face: once one pixel is looked up,
  // every face is needed.
  const bool pcss = p.filter == MapFilter::Pcss;
  const uint32_t all = nf >= 32 ? ~0u : (1u << nf) - 1u;
  // The AVX2 kernel (no normal offset) takes groups of 8 pixels; the scalar loop is its oracle
  // and takes the rest.
  const Faces8Fn faces8 = p.normal <= 0.0f ? faces8_simd() : nullptr;
  const MapLookupConsts consts =
      faces8 ? map_lookup_consts(scene, layout, p, {}) : MapLookupConsts{};
  // Faces (bit f: face f) and looked-up pixels of the pixels [b, e).
  auto scan = [&](size_t b, size_t e, uint32_t& f, size_t& count) {
    auto walk_taps = [&](int face, vec2 st) {
      for_each_pcf_tap(layout, face, st, p.pcf, [&](int ff, int, int, float) { f |= 1u << ff; });
    };
    size_t i = b;
    if (faces8)
      for (; i + 8 <= e; i += 8) {
        Receivers8 rest;
        const Faces8 r = faces8(consts, cross ? p.pcf : 1, &g.position[i].x, &g.geo_normal[i].x,
                                &g.covered[i], rest);
        f |= r.bits;
        if (pcss && r.looked_up) f |= all;
        count += r.looked_up;
        if (r.rest)
          for (int k = 0; k < 8; ++k)
            if (rest.active[k]) walk_taps(rest.face[k], vec2(rest.sx[k], rest.sy[k]));
      }
    for (; i < e; ++i) {
      if (!g.covered[i] || !faces_light(g, i, scene.light.position)) continue;
      vec2 st;
      if (projector && !projector_slide_coords(frame, scene.light.position, g.position[i], st))
        continue;
      ++count;
      if (pcss) f |= all;
      const vec3 to_p =
          lookup_point(layout, scene.light, p, g.position[i], g.geo_normal[i]) - scene.light.position;
      const int face = face_of(layout, to_p);
      f |= 1u << face;
      if (!cross) continue;
      // Interior pixels (the whole footprint inside the face) need nothing more: the per-tap
      // walk runs only within the filter's reach of a face edge.
      const LightFace& lf = layout.faces[size_t(face)];
      const vec2 c = face_texel_coords(lf, to_p);
      if (!pcf_taps_inside(c, p.pcf, lf.width, lf.height)) walk_taps(face, c);
    }
  };
  if (!looked_up) {
    // A sparse sample first (8 pixels of every 512): when it already needs every face, so does
    // the whole image, and the pass ends after 1/64 of the work. Otherwise every pixel is
    // walked below. Either way the answer is the exact set of faces (README "The light-map
    // pipeline": stage 2).
    uint32_t f = 0;
    size_t unused = 0;
    for (size_t b = 0; b < g.pixel_count() && f != all; b += 512)
      scan(b, std::min(b + 8, g.pixel_count()), f, unused);
    if (f == all) return std::vector<bool>(nf, true);
  }
  std::vector<uint32_t> flags(chunks, 0);  // bit f: face f needed
  std::vector<size_t> counts(chunks, 0);
  parallel_for_chunks(g.pixel_count(), grain, [&](size_t b, size_t e) {
    uint32_t f = 0;
    size_t count = 0;
    scan(b, e, f, count);
    flags[b / grain] = f;
    counts[b / grain] = count;
  });
  std::vector<bool> needed(nf, false);
  for (const uint32_t f : flags)
    for (size_t i = 0; i < nf; ++i) needed[i] = needed[i] || ((f >> i) & 1u);
  if (looked_up) {
    *looked_up = 0;
    for (size_t c : counts) *looked_up += c;
  }
  return needed;
}

void render_light_map(const Scene& scene, const MapParams& p, const std::vector<bool>& needed,
                      LightMap& map) {
  render_face_distances(scene, map.layout, needed, map.dist, CullMode::None, p.tess);
  for (size_t f = 0; f < map.dist.distance.size(); ++f)
    if (map.dist.rendered[f])
      quantize_depths(map.dist.distance[f].data(), map.dist.distance[f].size(), p.depth);
}

void filter_light_map(const MapParams& p, LightMap& map) {
  const size_t nf = map.layout.faces.size();
  map.a.resize(nf);
  map.b.resize(nf);
  map.max_depth.resize(nf);
  map.c.resize(nf);
  map.d.resize(nf);
  map_filter_ops(p.filter).filter(p, map);
}

void lookup_light_map(const Scene& scene, const GBuffer& g, const MapParams& p,
                      const LightMap& map, ImageF& mask, ImageU32* texels) {
  map_filter_ops(p.filter).lookup(scene, g, p, map, mask, texels);
}

const std::vector<const MapFilterOps*>& map_filters() {
  static const std::vector<const MapFilterOps*> rows = {&kDepthCompare, &kVarianceMap,
                                                        &kExponentialMap,
                                                        &kExponentialVarianceMap,
                                                        &kMomentShadowMap, &kPcss};
  return rows;
}

const MapFilterOps& map_filter_ops(MapFilter id) {
  for (const MapFilterOps* f : map_filters())
    if (f->id == id) return *f;
  SL_CHECK(false);
  return kDepthCompare;
}

namespace {

// Work of one repeat (README "Work counts"): texels a lookup reads and the bytes per texel.
void count_work(const MapParams& p, const LightMap& map, size_t looked_up, WorkCounts& w) {
  w.triangles_submitted = map.dist.triangles_submitted;
  w.triangles_binned = map.dist.triangles_binned;
  w.texels_rendered = map.dist.texels_rendered;
  w.pixels_looked_up = looked_up;
  const MapFilterOps& f = map_filter_ops(p.filter);
  const uint64_t planes = f.stored_planes(p);
  const uint64_t tap_bytes = f.tap_bytes(p);
  const uint64_t taps_per_lookup = f.taps_per_lookup(p);
  w.texels_filtered = planes * map.dist.texels_rendered;
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
  const uint64_t units = texels * (p.filter == MapFilter::Depth ? 1 : uint64_t(p.blur));
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
