#pragma once
// Parameters of every light-map technique: a layout × a filter.
//
// A technique's name is a layout letter plus a filter: c (cube), t (tetrahedral), p (the slide
// projector's one face), d (dual-paraboloid) + sm (depth compare with PCF), vsm (variance), esm
// (exponential), evsm, msm, pcss: csm, tsm, psm, dsm, cvsm, …, dpcss. One struct serves all of
// them. Every key is declared once (techniques/registry/technique_keys.h): the shared keys and the
// layouts' here (map_params.cpp), each filter's in its folder (techniques/filters/all.h lists
// them, and MapParams holds each one's keys struct); map_keys() assembles a
// technique's list, which parsing, --help and docs/techniques/keys.md read. The keys a technique
// does not declare are errors.
#include <string>
#include <vector>

#include "techniques/pipeline/depth_quantize.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/registry/technique_keys.h"
#include "techniques/registry/technique_spec.h"

// The filters' keys structs (each filter's header, techniques/filters/all.h).
#define SHADOWLAB_FILTER(id, ops)
#define SHADOWLAB_FILTER_KEYS(type, member)
#include "techniques/filters/all.h"
#undef SHADOWLAB_FILTER
#undef SHADOWLAB_FILTER_KEYS

namespace shadowlab {

// The filters, in the order of techniques/filters/all.h.
enum class MapFilter {
#define SHADOWLAB_FILTER(id, ops) id,
#define SHADOWLAB_FILTER_KEYS(type, member)
#include "techniques/filters/all.h"
#undef SHADOWLAB_FILTER
#undef SHADOWLAB_FILTER_KEYS
};

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
  // Each filter's own keys (vsm, esm, evsm, msm, pcss, …): the member its header names.
#define SHADOWLAB_FILTER(id, ops)
#define SHADOWLAB_FILTER_KEYS(type, member) type member;
#include "techniques/filters/all.h"
#undef SHADOWLAB_FILTER
#undef SHADOWLAB_FILTER_KEYS
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
