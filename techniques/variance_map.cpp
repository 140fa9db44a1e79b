// The variance filter ("vsm": cvsm, tvsm, pvsm): moments of the stored distance, box-filtered
// (techniques/moment_filter.h), looked up bilinearly and bounded by Chebyshev's inequality with
// the variance floor and the light-bleeding reduction; Krave's max-depth test and slope moment.
#include <algorithm>

#include "core/error.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup.h"

namespace shadowlab {
namespace {

void parse_keys(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  p.blur = r.get_int("blur", p.blur, 1, 63);
  if (p.blur % 2 == 0)
    throw InputError(flag, name + ": 'blur' must be odd, got " + std::to_string(p.blur));
  VsmKeys& v = p.vsm;
  v.min_variance = r.get_double("min_variance", v.min_variance, 0.0, 1e6);
  v.bleed = r.get_double("bleed", v.bleed, 0.0, 0.99);
  v.maxdepth_eps = r.get_double("maxdepth_eps", v.maxdepth_eps, 0.0, 1e3);
  v.slope_moment = r.get_bool("slope_moment", v.slope_moment);
  v.fp32 = r.get_bool("fp32", v.fp32);
}

std::string keys_text(const MapParams& p) {
  char b[200];
  std::snprintf(b, sizeof b, "blur=%d,min_variance=%g,bleed=%g,maxdepth_eps=%g,slope_moment=0,fp32=0",
                p.blur, p.vsm.min_variance, p.vsm.bleed, p.vsm.maxdepth_eps);
  return b;
}

void filter(const MapParams& p, LightMap& map) {
  for (size_t f = 0; f < map.layout.faces.size(); ++f) {
    if (!map.dist.rendered[f]) continue;
    const LightFace& face = map.layout.faces[f];
    const float* d = map.dist.distance[f].data();
    if (p.vsm.fp32)
      filter_moments_fp32(d, face.width, face.height, p.blur, p.vsm.slope_moment, map.a[f], map.b[f]);
    else
      filter_moments_double(d, face.width, face.height, p.blur, p.vsm.slope_moment, map.a[f],
                            map.b[f], map.scratch);
    if (p.vsm.maxdepth_eps > 0.0)
      filter_max(d, face.width, face.height, p.blur, map.max_depth[f], map.scratch);
  }
}

// Chebyshev's upper bound with the variance floor and the light-bleeding remap.
float chebyshev(double t, double mean, double var, double min_var, double bleed) {
  if (t <= mean) return 1.0f;
  var = std::max(var, min_var);
  const double diff = t - mean;
  double pmax = var / (var + diff * diff);
  if (bleed > 0.0) pmax = std::clamp((pmax - bleed) / (1.0 - bleed), 0.0, 1.0);
  return float(pmax);
}

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const FaceLayout& L = map.layout;
  const double inv_far = 1.0 / double(scene.light.far);
  const VsmKeys& v = p.vsm;
  const double min_var = v.min_variance * inv_far * inv_far;
  const double eps = v.maxdepth_eps * inv_far;
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
    if (v.maxdepth_eps > 0.0) {
      const std::vector<float>& mx = map.max_depth[fi];
      const double m = std::max(std::max(mx[idx[0]], mx[idx[1]]), std::max(mx[idx[2]], mx[idx[3]]));
      if (t > m + eps) return 0.0f;
    }
    const std::vector<float>& A = map.a[fi];
    const std::vector<float>& B = map.b[fi];
    if (v.fp32) {
      // The naive form in float: var = E[d²] − E[d]².
      float m1 = 0.0f, m2 = 0.0f;
      for (int k = 0; k < 4; ++k) {
        m1 += float(w[k]) * A[idx[k]];
        m2 += float(w[k]) * B[idx[k]];
      }
      return chebyshev(t, m1, double(m2 - m1 * m1), min_var, v.bleed);
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
    return chebyshev(t, mean, var, min_var, v.bleed);
  });
}

uint64_t taps_per_lookup(const MapParams&) { return 4; }  // bilinear
uint64_t stored_planes(const MapParams& p) { return 2 + (p.vsm.maxdepth_eps > 0.0 ? 1 : 0); }
uint64_t tap_bytes(const MapParams& p) { return 4 * stored_planes(p); }

}  // namespace

const MapFilterOps kVarianceMap = {"vsm", "variance shadow map", MapFilter::Variance, parse_keys,
                                   keys_text, filter, lookup, taps_per_lookup, tap_bytes,
                                   stored_planes};

}  // namespace shadowlab
