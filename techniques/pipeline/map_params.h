#pragma once
// Parameters of every light-map technique: a layout × a filter.
//
// A technique's name is a layout letter plus a filter: c (cube), t (tetrahedral), p (the slide
// projector's one face), d (dual-paraboloid) + sm (depth compare with PCF), vsm (variance), esm
// (exponential), evsm, msm, pcss: csm, tsm, psm, dsm, cvsm, …, dpcss. One struct serves all of
// them. Every key is declared once (techniques/registry/technique_keys.h): the shared keys and the
// layouts' here (map_params.cpp), each filter's in its own file; map_keys() assembles a
// technique's list, which parsing, --help and docs/techniques/keys.md read. The keys a technique
// does not declare are errors.
#include <string>
#include <vector>

#include "techniques/pipeline/depth_quantize.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/registry/technique_keys.h"
#include "techniques/registry/technique_spec.h"

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

// The members below hold no defaults of their own: each key's default, range and meaning is its
// declaration's (default_map_params stores them).

// Keys of the variance filter (vsm; techniques/filters/vsm/variance_map.cpp).
struct VsmKeys {
  double min_variance{};  // variance floor, m²
  double bleed{};         // light-bleeding reduction, p -> linstep(bleed, 1, p)
  double maxdepth_eps{};  // > 0: a receiver deeper than the footprint's max + eps (m) is shadowed
  bool slope_moment{};    // M2 = d² + ¼((∂d/∂x)² + (∂d/∂y)²) per texel
  bool fp32{};            // moments filtered in float (the naive form), not double
};

// Keys of the exponential filter (esm; techniques/filters/esm/exponential_map.cpp).
struct EsmKeys {
  double c{};  // exponent on normalised distance (|p - L| / far)
};

// Keys of the exponential variance filter (evsm; techniques/filters/evsm/exponential_variance_map.cpp). The
// exponents warp the normalised distance d' = 2d − 1 in [−1, 1].
struct EvsmKeys {
  int moments{};          // 2: the positive warp e^(c_pos·d'); 4: also −e^(−c_neg·d')
  double c_pos{};         // positive exponent
  double c_neg{};         // negative exponent
  double min_variance{};  // variance floor of the distance, m², carried into each warp
  double bleed{};         // light-bleeding reduction, as for vsm
};

// Keys of the moment filter (msm; techniques/filters/msm/moment_bound.h). The moments are filtered in float
// and stored as 4 floats per texel, or (quantize16) through Peters & Klein's optimized 16-bit
// quantization, whose coarser rounding needs the larger default α.
struct MsmKeys {
  bool hausdorff{};   // variant=hausdorff (support [0, 1]) instead of hamburger (support ℝ)
  bool quantize16{};  // store 4 × 16 bits instead of 4 × fp32
  double alpha{};     // moment bias toward (½, ½, ½, ½)
};

// Keys of percentage-closer soft shadows (pcss; techniques/filters/pcss/pcss.cpp): a blocker search, the
// penumbra width from the mean blocker distance, then rotated Poisson PCF over that width.
struct PcssKeys {
  double light_size{};   // light radius, m; < 0: the scene light's radius
  int search{};          // blocker-search taps (rotated Poisson disk)
  int taps{};            // PCF taps (rotated Poisson disk)
  double search_near{};  // nearest blocker searched for, × the receiver's distance
  bool model{};          // the penumbra from techniques/filters/pcss/penumbra_model.h, not the mean blocker
};

struct MapParams {
  FaceLayoutKind layout = FaceLayoutKind::Cube;
  MapFilter filter = MapFilter::Depth;
  int res{};              // cube face edge N; the tetrahedral texture has ~6·N² texels;
                          // projector: height N, width round(N × aspect), guard excluded
  DepthFormat depth = DepthFormat::F32;  // stored precision, quantized before any filtering
  // Bias modes, metres, applied to the receiver's radial distance before comparison:
  float bias{};           // constant
  float slope{};          // × texel size at the receiver × tan(angle to light) (tan <= 10) × filter reach
  float normal{};         // normal offset: lookup point moved along the geometric normal by
                          // normal × texel size at the receiver × (1 - N·L)
  int pcf{};              // depth: 1 = nearest texel, odd N >= 3 = N×N bilinear-weighted taps
  PcfKind pcf_kind = PcfKind::Grid;  // depth: grid, or poisson (needs pcf >= 3 and the guard band)
  int taps{};             // depth, poisson: taps per pixel
  bool rpdb{};            // depth compare and pcss: each tap compares with the receiver plane's
                          // depth at the tap (techniques/lookup/map_receiver.h) instead of the slope term
  SeamMode seams = SeamMode::Guard;  // depth compare: guard band or cross-face taps
  int tess{};             // dual-paraboloid layout: split triangles whose image has an edge
                          // longer than tess texels before projection (0 = off)
  int blur{};             // moment maps: separable box filter width, texels (odd; 1 = none)
  VsmKeys vsm;
  EsmKeys esm;
  EvsmKeys evsm;
  MsmKeys msm;
  PcssKeys pcss;
};

using MapKey = KeyDecl<MapParams>;

// Every key of a layout × filter in reading order: the shared keys, the layout's, the filter's
// (MapFilterOps::keys), with the defaults and ranges that depend on the pair.
std::vector<MapKey> map_keys(FaceLayoutKind layout, MapFilter filter);
// `blur`, the box width every filtering technique takes; `rpdb`, the receiver-plane depth bias
// of depth compare and pcss. Declared once here, listed by the filters that read them.
MapKey map_blur_key();
MapKey map_rpdb_key();
// The declared defaults of a layout × filter.
MapParams default_map_params(FaceLayoutKind layout, MapFilter filter);
// Parses and range-checks a spec for the given layout × filter (InputError names `flag` and
// the key; unknown keys are errors).
MapParams parse_map_params(const TechniqueSpec& spec, FaceLayoutKind layout, MapFilter filter,
                           const char* flag);
// Guard texels each face needs so that every tap and filter stays inside the face's image
// (0 with SeamMode::Cross).
int map_guard(const MapParams& p);
// The filter's reach in texels that scales the slope bias: PCF (pcf + 1)/2; moment maps 1.
float map_reach(const MapParams& p);

}  // namespace shadowlab
