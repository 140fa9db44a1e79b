#pragma once
// Parameters of every light-map technique: a layout × a filter (README "Techniques").
//
// A technique's name is a layout letter plus a filter: c (cube), t (tetrahedral), p (the slide
// projector's one face), d (dual-paraboloid) + sm (depth compare with PCF), vsm (variance), esm
// (exponential), evsm, msm, pcss: csm, tsm, psm, dsm, cvsm, …, dpcss. One struct and one parser
// serve all of them; the keys a filter does not use are errors.
//
// Shared keys: res (comparable cube edge N; psm: the map's height), bias (m), slope, normal,
// depth (stored precision, techniques/depth_quantize.h); d only: tess. Depth compare: pcf,
// seams, pcf_kind, taps, rpdb. Filters: blur. VSM: min_variance (m²), bleed, maxdepth_eps (m),
// slope_moment, fp32. ESM: c.
// EVSM (evsm: cevsm, tevsm, pevsm): moments, c_pos, c_neg, min_variance, bleed.
// MSM (msm: cmsm, tmsm, pmsm): variant, alpha, quantize16.
// PCSS (pcss: cpcss, tpcss, ppcss): light_size, search, taps, search_near, rpdb.
#include <string>

#include "techniques/depth_quantize.h"
#include "techniques/light_faces.h"
#include "techniques/technique_spec.h"

namespace shadowlab {

enum class MapFilter { Depth, Variance, Exponential, ExponentialVariance, Moment, Pcss };

// How taps near a face's edge read their texels.
//   Guard: every face is rendered wider by a guard band of (reach + 1) texels, so every tap
//          stays inside the face's own image (the only way for blurs, which run per face).
//   Cross: no guard band; a tap beyond the face's image is looked up through its direction in
//          the face that owns it. Depth compare only.
enum class SeamMode { Guard, Cross };

// The PCF footprint of depth compare (pcf > 1): the N×N grid of bilinear-weighted taps, or
// `taps` Poisson-disk taps over a disk of diameter pcf texels, rotated per pixel by an angle
// from the counter-based random numbers (core/rng.h: a function of the pixel, never the
// thread), each a bilinear-weighted compare.
enum class PcfKind { Grid, Poisson };

// Keys of the variance filter (vsm).
struct VsmKeys {
  double min_variance = 1e-6;  // variance floor, m² (1 mm standard deviation)
  double bleed = 0.0;          // light-bleeding reduction, p -> linstep(bleed, 1, p)
  double maxdepth_eps = 0.0;   // (Krave) > 0 stores the footprint's max depth; a receiver
                               // deeper than max + eps (m) is fully shadowed
  bool slope_moment = false;   // (Krave) M2 = d² + ¼((∂d/∂x)² + (∂d/∂y)²) per texel
  bool fp32 = false;           // fp32 moments (d, d²) filtered in float — the naive form, kept
                               // to measure its cancellation; default: double filter, stored
                               // as (mean, variance)
};

// Keys of the exponential filter (esm).
struct EsmKeys {
  double c = 200.0;  // exponent on normalised distance (|p - L| / far); the log-space filter
                     // allows any c <= 700 (README: why 200)
};

// Keys of the exponential variance filter (evsm). The exponents warp the normalised distance
// d' = 2d − 1 in [−1, 1]; e^(2c) must stay below FLT_MAX (c <= 44.36) in the stored moments.
struct EvsmKeys {
  int moments = 2;             // 2: the positive warp e^(c_pos·d'); 4: also −e^(−c_neg·d')
  double c_pos = 40.0;         // positive exponent (the fp32 default of the literature)
  double c_neg = 5.0;          // negative exponent
  double min_variance = 1e-6;  // variance floor of the distance, m², carried into each warp
                               // by its slope at the receiver
  double bleed = 0.0;          // light-bleeding reduction, as for vsm
};

// Keys of the moment filter (msm; techniques/moment_bound.h). The moments are filtered in
// double and stored as 4 floats per texel, or (quantize16) through Peters & Klein's optimized
// 16-bit quantization, whose coarser rounding needs the larger default α.
struct MsmKeys {
  bool hausdorff = false;   // variant=hamburger (support ℝ) | hausdorff (support [0, 1])
  bool quantize16 = false;  // store 4 × 16 bits (the optimized quantization) instead of 4 × fp32
  double alpha = 3e-6;      // moment bias toward (½, ½, ½, ½); default 3e-6 (fp32), 3e-5 with
                            // quantize16
};

// Keys of percentage-closer soft shadows (pcss; techniques/pcss.cpp): a blocker search, the
// penumbra width from the mean blocker distance, then rotated Poisson PCF over that width.
struct PcssKeys {
  double light_size = -1.0;  // light radius, m; < 0: the scene light's radius ("light")
  int search = 16;           // blocker-search taps (rotated Poisson disk)
  int taps = 32;             // PCF taps (rotated Poisson disk)
  double search_near = 0.25; // nearest blocker searched for, as a fraction of the receiver's
                             // distance (sets the search disk: README "PCSS")
  bool model = false;        // estimate=model: the penumbra from the blockers' depth range by
                             // techniques/penumbra_model.h instead of the mean blocker ratio
};

struct MapParams {
  FaceLayoutKind layout = FaceLayoutKind::Cube;
  MapFilter filter = MapFilter::Depth;
  int res = 512;          // cube face edge N; the tetrahedral texture has ~6·N² texels;
                          // projector: height N, width round(N × aspect), guard excluded
  DepthFormat depth = DepthFormat::F32;  // stored precision, quantized before any filtering
  // Bias modes, metres, applied to the receiver's radial distance before comparison:
  float bias = 0.01f;     // constant
  float slope = 1.0f;     // × texel size at the receiver × tan(angle to light) (tan <= 10) × filter reach
  float normal = 0.0f;    // normal offset: lookup point moved along the geometric normal by
                          // normal × texel size at the receiver × (1 - N·L)
  int pcf = 1;            // depth: 1 = nearest texel, odd N >= 3 = N×N bilinear-weighted taps
  PcfKind pcf_kind = PcfKind::Grid;  // depth: grid, or poisson (needs pcf >= 3 and the guard band)
  int taps = 16;          // depth, poisson: taps per pixel
  bool rpdb = false;      // depth compare and pcss: receiver-plane depth bias: each tap compares
                          // with the receiver plane's depth at the tap (its gradient in the
                          // face's texel space, techniques/map_receiver.h) instead of the slope
                          // term; needs the guard band
  SeamMode seams = SeamMode::Guard;  // depth: default Cross on the cube layout (csm's own
                                     // mechanism, kept byte for byte), Guard elsewhere
  int tess = 0;           // dual-paraboloid layout: split triangles whose image has an edge
                          // longer than tess texels before projection (0 = off)
  int blur = 3;           // moment maps: separable box filter width, texels (odd; 1 = none)
  VsmKeys vsm;            // the variance filter's own keys (techniques/variance_map.cpp)
  EsmKeys esm;            // the exponential filter's own keys (techniques/exponential_map.cpp)
  EvsmKeys evsm;          // the exponential variance filter's (techniques/exponential_variance_map.cpp)
  MsmKeys msm;            // the moment filter's (techniques/moment_shadow_map.cpp)
  PcssKeys pcss;          // percentage-closer soft shadows' (techniques/pcss.cpp)
};

// The defaults of a layout × filter before any key is read (bias and slope are 0 for the
// filtering techniques: the filter itself absorbs a surface's own depth variation).
MapParams default_map_params(FaceLayoutKind layout, MapFilter filter);
// Parses and range-checks a spec for the given layout × filter (InputError names `flag` and
// the key; unknown keys are errors).
MapParams parse_map_params(const TechniqueSpec& spec, FaceLayoutKind layout, MapFilter filter,
                           const char* flag);
// Reads `blur` (odd, 1..63), the box width every filtering technique takes.
void read_blur(SpecReader& r, const std::string& name, const char* flag, MapParams& p);
// "key=default,…" of a layout × filter, for --list-techniques and --help.
std::string map_keys_text(FaceLayoutKind layout, MapFilter filter);
// Reads `rpdb` (depth compare, pcss): with rpdb=1 the slope term is off (an explicit slope > 0
// is an error).
void read_rpdb(SpecReader& r, const std::string& name, const char* flag, MapParams& p);
// Guard texels each face needs so that every tap and filter stays inside the face's image
// (0 with SeamMode::Cross).
int map_guard(const MapParams& p);
// The filter's reach in texels that scales the slope bias: PCF (pcf + 1)/2; moment maps 1.
float map_reach(const MapParams& p);

}  // namespace shadowlab
