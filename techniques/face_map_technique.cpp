#include "techniques/face_map_technique.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/timer.h"
#include "techniques/face_map_lookup.h"
#include "techniques/moment_filter.h"

namespace shadowlab {

std::vector<bool> faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                               const FaceMapParams& p) {
  const size_t grain = 8192;
  const size_t chunks = (g.pixel_count() + grain - 1) / grain;
  const size_t nf = layout.faces.size();
  const bool projector = layout.kind == FaceLayoutKind::Projector;
  const ProjectorFrame frame = projector ? projector_frame(scene.projector) : ProjectorFrame{};
  std::vector<std::vector<char>> flags(chunks, std::vector<char>(nf, 0));
  parallel_for_chunks(g.pixel_count(), grain, [&](size_t b, size_t e) {
    std::vector<char>& f = flags[b / grain];
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i] || !faces_light(g, i, scene.light.position)) continue;
      vec2 st;
      if (projector && !projector_slide_coords(frame, scene.light.position, g.position[i], st))
        continue;
      const vec3 to_p = g.position[i] - scene.light.position;
      // The lookup's face: of the receiver itself, or of its normal-offset point.
      f[size_t(p.normal > 0.0f
                   ? make_receiver(layout, scene.light, p, 1.0f, g.position[i], g.geo_normal[i]).face
                   : face_of(layout, to_p))] = 1;
    }
  });
  std::vector<bool> needed(nf, false);
  for (const auto& f : flags)
    for (size_t i = 0; i < nf; ++i) needed[i] = needed[i] || f[i];
  return needed;
}

void build_face_map(const Scene& scene, const FaceMapParams& p, const std::vector<bool>& needed,
                    FaceMap& map) {
  render_face_distances(scene, map.layout, needed, map.dist);
  for (size_t f = 0; f < map.dist.distance.size(); ++f)
    if (map.dist.rendered[f])
      quantize_depths(map.dist.distance[f].data(), map.dist.distance[f].size(), p.depth);
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

}  // namespace

void lookup_face_map(const Scene& scene, const GBuffer& g, const FaceMapParams& p,
                     const FaceMap& map, ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double inv_far = 1.0 / double(scene.light.far);
  if (p.filter == MapFilter::Depth) {
    const int half = (p.pcf - 1) / 2;
    const float norm = 1.0f / float(p.pcf * p.pcf);
    lookup_faces(scene, g, L, p, 0.5f * float(p.pcf + 1), mask, texels, [&](const Receiver& r) {
      const LightFace& f = L.faces[size_t(r.face)];
      const float* depth = map.dist.distance[size_t(r.face)].data();
      auto at = [&](int x, int y) {
        return depth[size_t(std::clamp(y, 0, f.height - 1)) * size_t(f.width) +
                     size_t(std::clamp(x, 0, f.width - 1))];
      };
      if (p.pcf <= 1)
        return r.depth <= at(int(std::max(r.st.x, -1.0f)), int(std::max(r.st.y, -1.0f))) ? 1.0f
                                                                                          : 0.0f;
      // N×N comparisons, each bilinear-weighted: an (N+1)² texel footprint.
      const Bilinear bl = bilinear_taps(r.st, f.width, f.height);
      const int bx = int(std::floor(r.st.x - 0.5f)), by = int(std::floor(r.st.y - 0.5f));
      float lit = 0.0f, total = 0.0f;
      for (int j = 0; j <= p.pcf; ++j) {
        const float wy = j == 0 ? 1.0f - bl.fy : (j == p.pcf ? bl.fy : 1.0f);
        for (int i = 0; i <= p.pcf; ++i) {
          const float wx = i == 0 ? 1.0f - bl.fx : (i == p.pcf ? bl.fx : 1.0f);
          const float w = wx * wy * norm;
          total += w;
          lit += r.depth <= at(bx - half + i, by - half + j) ? w : 0.0f;
        }
      }
      return total > 0.0f ? lit / total : 1.0f;
    });
    return;
  }
  if (p.filter == MapFilter::Exponential) {
    const double c = p.c;
    lookup_faces(scene, g, L, p, 1.0f, mask, texels, [&](const Receiver& r) {
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
  lookup_faces(scene, g, L, p, 1.0f, mask, texels, [&](const Receiver& r) {
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

ShadowResult run_face_map_technique(const TechniqueSpec& spec, const Scene& scene,
                                    const GBuffer& gbuffer, const RunOptions& options) {
  const FaceMapParams p = parse_face_map_params(spec, options.flag);
  FaceMap map;
  const int guard = face_map_guard(p);
  if (p.layout == FaceLayoutKind::Projector && !scene.projector.enabled)
    throw InputError(options.flag, spec.name + " needs a slide projector light (--slide)");
  map.layout = p.layout == FaceLayoutKind::Cube        ? cube_layout(p.res, guard)
               : p.layout == FaceLayoutKind::Projector ? projector_layout(scene.projector, p.res, guard)
                                                       : tetra_layout(p.res, guard);
  ShadowResult r;
  r.faces_total = int(map.layout.faces.size());
  std::vector<bool> needed;
  std::vector<double> map_t, lookup_t;
  for (int rep = 0; rep < std::max(1, options.repeats); ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    needed = faces_needed(scene, gbuffer, map.layout, p);
    build_face_map(scene, p, needed, map);
    map_t.push_back(ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    lookup_face_map(scene, gbuffer, p, map, r.mask, options.want_texels ? &r.texels : nullptr);
    lookup_t.push_back(ms_since(t0));
  }
  r.map_ms = median(map_t);
  r.lookup_ms = median(lookup_t);
  for (bool n : needed) r.faces_needed += n ? 1 : 0;
  r.faces_rendered = r.faces_needed;
  r.triangles_submitted = map.dist.triangles_submitted;
  r.triangles_culled = map.dist.triangles_culled;
  const LightFace& f0 = map.layout.faces[0];
  r.notes = "faces " + std::to_string(r.faces_rendered) + "/" + std::to_string(r.faces_total) +
            " rendered (" + std::to_string(f0.width) + "x" + std::to_string(f0.height) +
            " texels each, guard " + std::to_string(map.layout.guard) + "), " +
            std::to_string(r.triangles_culled) + " of " + std::to_string(r.triangles_submitted) +
            " triangle submissions culled before binning";
  return r;
}

}  // namespace shadowlab
