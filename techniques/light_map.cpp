#include "techniques/light_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/timer.h"
#include "techniques/map_lookup_simd.h"
#include "techniques/map_receiver.h"

namespace shadowlab {

FaceLayout map_layout(const MapParams& p, const Scene& scene) {
  const int guard = map_guard(p);
  switch (p.layout) {
    case FaceLayoutKind::Cube: return cube_layout(p.res, guard);
    case FaceLayoutKind::Tetrahedron: return tetra_layout(p.res, guard);
    case FaceLayoutKind::Projector: return projector_layout(scene.projector, p.res, guard);
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
  // The AVX2 kernel (no normal offset) takes groups of 8 pixels; the scalar loop is its oracle
  // and takes the rest.
  const Faces8Fn faces8 = p.normal <= 0.0f ? faces8_simd() : nullptr;
  const MapLookupConsts consts =
      faces8 ? map_lookup_consts(scene, layout, p, {}) : MapLookupConsts{};
  std::vector<uint32_t> flags(chunks, 0);  // bit f: face f needed
  std::vector<size_t> counts(chunks, 0);
  parallel_for_chunks(g.pixel_count(), grain, [&](size_t b, size_t e) {
    uint32_t f = 0;
    size_t count = 0;
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
  render_face_distances(scene, map.layout, needed, map.dist);
  for (size_t f = 0; f < map.dist.distance.size(); ++f)
    if (map.dist.rendered[f])
      quantize_depths(map.dist.distance[f].data(), map.dist.distance[f].size(), p.depth);
}

void filter_light_map(const MapParams& p, LightMap& map) {
  const size_t nf = map.layout.faces.size();
  map.a.resize(nf);
  map.b.resize(nf);
  map.max_depth.resize(nf);
  if (p.filter == MapFilter::Depth) return;
  for (size_t f = 0; f < nf; ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    const float* d = map.dist.distance[f].data();
    if (p.filter == MapFilter::Exponential) {
      filter_esm_log(d, face.width, face.height, p.blur, p.c, map.a[f], map.scratch);
      continue;
    }
    if (p.moments_fp32)
      filter_moments_fp32(d, face.width, face.height, p.blur, p.slope_moment, map.a[f], map.b[f]);
    else
      filter_moments_double(d, face.width, face.height, p.blur, p.slope_moment, map.a[f], map.b[f],
                            map.scratch);
    if (p.maxdepth_eps > 0.0)
      filter_max(d, face.width, face.height, p.blur, map.max_depth[f], map.scratch);
  }
}

namespace {

// Chebyshev's upper bound with the variance floor and the light-bleeding remap.
float chebyshev(double t, double mean, double var, double min_var, double bleed) {
  if (t <= mean) return 1.0f;
  var = std::max(var, min_var);
  const double diff = t - mean;
  double pmax = var / (var + diff * diff);
  if (bleed > 0.0) pmax = std::clamp((pmax - bleed) / (1.0 - bleed), 0.0, 1.0);
  return float(pmax);
}

// No SIMD block: every pixel runs the scalar loop.
size_t no_block(size_t, size_t) { return 0; }

// The receivers of a SIMD group's lanes, for the scalar visibility of the lanes `r.active` marks.
Receiver lane_receiver(const Receivers8& r, int k) {
  Receiver rc;
  rc.face = r.face[k];
  rc.st = vec2(r.sx[k], r.sy[k]);
  rc.depth = r.depth[k];
  rc.texel = uint32_t(r.texel[k]);
  return rc;
}

// Runs the pixel loop with the AVX2 kernels in front where they apply (no normal offset; the
// scalar loop, their oracle, handles the rest): the receivers of 8 pixels at a time, then the
// one-tap or N×N compare in vector form (depth), or `visibility` per lane (the moment maps).
template <class Visibility>
void lookup_pixels(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
                   ImageF& mask, ImageU32* texels, const Visibility& visibility) {
  const FaceLayout& L = map.layout;
  const Receivers8Fn receivers8 = p.normal <= 0.0f ? receivers8_simd() : nullptr;
  if (!receivers8) {
    lookup_faces(scene, g, L, p, mask, texels, visibility, no_block);
    return;
  }
  const MapLookupConsts c = map_lookup_consts(scene, L, p, map.dist.distance);
  const bool depth = p.filter == MapFilter::Depth && c.gather_ok;
  const Depth1Fn depth1 = depth && p.pcf <= 1 ? depth1_simd() : nullptr;
  const PcfFn pcf = depth && p.pcf > 1 ? pcf_simd() : nullptr;
  lookup_faces(scene, g, L, p, mask, texels, visibility, [&](size_t b, size_t e) {
    size_t i = b;
    for (; i + 8 <= e; i += 8) {
      const float* pos = &g.position[i].x;
      const float* nrm = &g.geo_normal[i].x;
      float* m = &mask.data[i];
      uint32_t* t = texels ? &texels->data[i] : nullptr;
      if (depth1) {
        depth1(c, pos, nrm, &g.covered[i], m, t);
        continue;
      }
      Receivers8 r;
      if (pcf) {
        pcf(c, p.pcf, pos, nrm, &g.covered[i], m, t, r);
      } else {
        receivers8(c, pos, nrm, &g.covered[i], r);
        for (int k = 0; k < 8; ++k) {
          m[k] = r.mask[k];
          if (t) t[k] = uint32_t(r.texel[k]);
        }
      }
      for (int k = 0; k < 8; ++k) {
        if (!r.active[k]) continue;
        const Receiver rc = lane_receiver(r, k);
        m[k] = std::clamp(visibility(rc), 0.0f, 1.0f);
        if (t) t[k] = rc.texel;
      }
    }
    return i - b;
  });
}

void lookup_depth(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
                  ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    // Lit weight over total weight: both sums see the same additions, so an all-lit
    // footprint gives exactly 1 whatever the float rounding of the weights.
    float lit = 0.0f, total = 0.0f;
    for_each_pcf_tap(L, r.face, r.st, p.pcf, [&](int f, int x, int y, float w) {
      const LightFace& lf = L.faces[size_t(f)];
      total += w;
      lit += r.depth <= map.dist.distance[size_t(f)][size_t(y) * size_t(lf.width) + size_t(x)] ? w : 0.0f;
    });
    return total > 0.0f ? std::min(lit / total, 1.0f) : 1.0f;
  });
}

}  // namespace

void lookup_light_map(const Scene& scene, const GBuffer& g, const MapParams& p,
                      const LightMap& map, ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double inv_far = 1.0 / double(scene.light.far);
  if (p.filter == MapFilter::Depth) {
    lookup_depth(scene, g, p, map, mask, texels);
    return;
  }
  if (p.filter == MapFilter::Exponential) {
    const double c = p.c;
    lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
      const LightFace& f = L.faces[size_t(r.face)];
      const float* z = map.a[size_t(r.face)].data();
      const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
      const float ct = float(c) * r.depth;
      // Σ w·exp(c·z_occ − c·t): the bilinear filter of exp(c·z) times exp(−c·t). Each exponent
      // is capped at 80 (e^80 ≈ 5.5e34, so four terms stay finite in float): any such tap already
      // makes the sum >= 1 unless its weight is below e^-80, and the result is clamped to 1.
      auto term = [&](int x, int y) {
        return std::exp(std::min(z[size_t(y) * size_t(f.width) + size_t(x)] - ct, 80.0f));
      };
      const float v = (1.0f - bl.fy) * ((1.0f - bl.fx) * term(bl.x0, bl.y0) + bl.fx * term(bl.x1, bl.y0)) +
                      bl.fy * ((1.0f - bl.fx) * term(bl.x0, bl.y1) + bl.fx * term(bl.x1, bl.y1));
      return std::min(v, 1.0f);
    });
    return;
  }
  // Variance.
  const double min_var = p.min_variance * inv_far * inv_far;
  const double eps = p.maxdepth_eps * inv_far;
  lookup_pixels(scene, g, p, map, mask, texels, [&](const Receiver& r) {
    const size_t fi = size_t(r.face);
    const LightFace& f = L.faces[fi];
    const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
    const size_t idx[4] = {size_t(bl.y0) * size_t(f.width) + size_t(bl.x0),
                           size_t(bl.y0) * size_t(f.width) + size_t(bl.x1),
                           size_t(bl.y1) * size_t(f.width) + size_t(bl.x0),
                           size_t(bl.y1) * size_t(f.width) + size_t(bl.x1)};
    const double w[4] = {(1.0 - bl.fx) * (1.0 - bl.fy), double(bl.fx) * (1.0 - bl.fy),
                         (1.0 - bl.fx) * double(bl.fy), double(bl.fx) * double(bl.fy)};
    const double t = double(r.depth);
    if (p.maxdepth_eps > 0.0) {
      const std::vector<float>& mx = map.max_depth[fi];
      const double m = std::max(std::max(mx[idx[0]], mx[idx[1]]), std::max(mx[idx[2]], mx[idx[3]]));
      if (t > m + eps) return 0.0f;
    }
    const std::vector<float>& A = map.a[fi];
    const std::vector<float>& B = map.b[fi];
    if (p.moments_fp32) {
      // The naive form in float: var = E[d²] − E[d]².
      float m1 = 0.0f, m2 = 0.0f;
      for (int k = 0; k < 4; ++k) {
        m1 += float(w[k]) * A[idx[k]];
        m2 += float(w[k]) * B[idx[k]];
      }
      return chebyshev(t, m1, double(m2 - m1 * m1), min_var, p.bleed);
    }
    // Centred: the mixture of the four texels' (mean, variance) has variance
    // Σ w·var + Σ w·(mean − mean̄)², with no cancellation.
    double mean = 0.0;
    for (int k = 0; k < 4; ++k) mean += w[k] * A[idx[k]];
    double var = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double dm = A[idx[k]] - mean;
      var += w[k] * (double(B[idx[k]]) + dm * dm);
    }
    return chebyshev(t, mean, var, min_var, p.bleed);
  });
}

namespace {

// Work of one repeat (README "Work counts"): texels a lookup reads and the bytes per texel.
void count_work(const MapParams& p, const LightMap& map, size_t looked_up, WorkCounts& w) {
  w.triangles_submitted = map.dist.triangles_submitted;
  w.triangles_binned = map.dist.triangles_binned;
  w.texels_rendered = map.dist.texels_rendered;
  w.pixels_looked_up = looked_up;
  // Planes the filter produces per texel, and bytes a lookup reads per tap.
  uint64_t planes = 0, tap_bytes = 4;
  uint64_t taps_per_lookup = 4;  // bilinear
  if (p.filter == MapFilter::Depth) {
    taps_per_lookup = p.pcf <= 1 ? 1 : uint64_t(p.pcf + 1) * uint64_t(p.pcf + 1);
  } else if (p.filter == MapFilter::Exponential) {
    planes = 1;
  } else {
    planes = 2 + (p.maxdepth_eps > 0.0 ? 1 : 0);
    tap_bytes = 4 * planes;
  }
  w.texels_filtered = planes * map.dist.texels_rendered;
  w.taps = taps_per_lookup * looked_up;
  w.bytes_written = 4 * (map.dist.texels_rendered + w.texels_filtered);
  w.bytes_read = tap_bytes * w.taps;
}

}  // namespace

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
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    needed = faces_needed(scene, gbuffer, map.layout, p, &looked_up);
    faces_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    render_light_map(scene, p, needed, map);
    render_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    filter_light_map(p, map);
    filter_t.push_back(ms_since(t0));
    map_t.push_back(faces_t.back() + render_t.back() + filter_t.back());
    t0 = std::chrono::steady_clock::now();
    lookup_light_map(scene, gbuffer, p, map, r.mask, options.want_texels ? &r.texels : nullptr);
    lookup_t.push_back(ms_since(t0));
  }
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
