#pragma once
// AVX2 kernels of the light-map lookup (techniques/pipeline/light_map.h), 8 GBuffer pixels at a time, for
// every layout (no normal offset):
//   receivers  face, texel coordinates, texel index and biased depth of each pixel, exactly as
//              make_receiver() computes them (techniques/lookup/map_receiver.h), for any filter;
//   depth1     the one-tap compare (pcf=1);
//   pcf        the N×N bilinear-weighted compare for pixels whose footprint lies inside their
//              face's image; the others are left to the scalar tap walk;
//   faces8     the faces some pixel's lookup needs (the pipeline's stage 2).
// Each performs the same IEEE operations in the same order as the scalar lookup (its oracle), so
// masks and texel indices are bit-identical: tests/techniques/lookup_simd_test.cpp checks them at
// the comparison's threshold, and whole renders with SHADOWLAB_SCALAR=1 (the scalar table)
// against the default. The kernels are one family, LookupKernels (docs/simd.md).
#include <cstdint>
#include <vector>

#include "core/aligned_vector.h"
#include "core/isa.h"
#include "core/math.h"
#include "core/scene.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/pipeline/map_params.h"

namespace shadowlab {

// Per-face constants in lanes 0..5 (one face per lane), plus the scalars.
struct MapLookupConsts {
  vec3 light{0.0f};
  float inv_far = 0.0f;
  float bias = 0.0f;             // constant bias, metres
  float slope_k = 0.0f;          // slope × reach (make_receiver's k)
  float plane_texel = 0.0f;      // face 0's plane texel size
  FaceLayoutKind kind = FaceLayoutKind::Cube;
  vec3 proj_forward{0.0f}, proj_right{0.0f}, proj_up{0.0f};  // projector gate
  float proj_tan_x = 0.0f, proj_tan_y = 0.0f;
  alignas(32) float fwd[3][8] = {}, right[3][8] = {}, up[3][8] = {};
  alignas(32) float left[8] = {}, range_u[8] = {}, top[8] = {}, range_v[8] = {};
  alignas(32) float width_f[8] = {}, height_f[8] = {};
  alignas(32) int32_t width[8] = {}, height[8] = {}, base[8] = {};
  // Stored distances: face f's texel i is depth_base[offset[f] + i] (offsets in floats from the
  // lowest rendered face's storage; gathers need one base). gather_ok is false when the faces'
  // storage lies too far apart for 32-bit offsets (then only the scalar loops run).
  alignas(32) int32_t offset[8] = {};
  const float* depth_base = nullptr;
  bool gather_ok = false;
};

MapLookupConsts map_lookup_consts(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                                  const std::vector<LineAlignedFloats>& face_depth);

// Receivers of 8 pixels. Inactive lanes (uncovered, facing away, outside the projector) carry
// their final mask (1 uncovered, else 0) and texel kNoTexel.
struct Receivers8 {
  alignas(32) float sx[8], sy[8], depth[8], mask[8];
  alignas(32) int32_t face[8], texel[8], active[8];
};

using Receivers8Fn = void (*)(const MapLookupConsts& c, const float* pos, const float* nrm,
                              const uint8_t* covered, Receivers8& out);
using Depth1Fn = void (*)(const MapLookupConsts& c, const float* pos, const float* nrm,
                          const uint8_t* covered, float* mask, uint32_t* texels);
// Writes mask and texels of every lane but the active lanes whose footprint leaves the face's
// image: those are returned in `rest` (rest.active set) for the scalar tap walk.
using PcfFn = void (*)(const MapLookupConsts& c, int pcf, const float* pos, const float* nrm,
                       const uint8_t* covered, float* mask, uint32_t* texels, Receivers8& rest);

// Faces needed by 8 pixels: `bits` has bit f set when an active lane's face is f; `looked_up`
// counts the active lanes. With cross_pcf > 1 (SeamMode::Cross), lanes whose footprint leaves
// their face are returned in `rest` (rest.active, sx, sy, face; `rest` true when any) for the
// scalar tap walk.
struct Faces8 {
  uint32_t bits = 0, looked_up = 0;
  bool rest = false;
};
using Faces8Fn = Faces8 (*)(const MapLookupConsts& c, int cross_pcf, const float* pos,
                            const float* nrm, const uint8_t* covered, Receivers8& rest);

// Per-face float planes (a filter's map.a, map.max_depth, a layout's distances) seen from one base with 32-bit offsets in
// floats, like the distances in MapLookupConsts; ok is false when they lie too far apart.
struct PlaneGather {
  const float* base = nullptr;
  alignas(32) int32_t offset[8] = {};
  bool ok = false;
};
PlaneGather plane_gather(const std::vector<std::vector<float>>& planes);
PlaneGather plane_gather(const std::vector<LineAlignedFloats>& planes);

// The bilinear footprint of 8 receivers (bilinear_taps: texels (x0, y0) … (x0 + 1, y0 + 1)
// clamped to the face, fractions fx, fy) and, for the active lanes, the 4 tap values of each of
// n planes: values[plane][tap][lane], taps in the order (x0,y0), (x1,y0), (x0,y1), (x1,y1).
using Bilinear8Fn = void (*)(const MapLookupConsts& c, const Receivers8& r,
                             const PlaneGather* planes, int n, float (*values)[4][8], float* fx,
                             float* fy);

// The same footprint in one plane holding two (or four) values per texel, interleaved (texel i's
// at plane.base[offset[face] + 2i] and [+ 2i + 1]): values[value][tap][lane], value 0 or 1.
using Bilinear8x2Fn = void (*)(const MapLookupConsts& c, const Receivers8& r,
                               const PlaneGather& plane, float (*values)[4][8], float* fx,
                               float* fy);

// bilinear8_interleaved4 (LookupKernels): the same for four values per texel (texel i's at
// offset + 4i + 0..3): values[0..3][tap][lane].

// The bilinear mix of four values per texel (texel i's at offset + 4i + 0..3) for 8 receivers,
// in double: m[v][lane] = Σ_t w_t · values[v][t][lane], with bilinear_weights' w (chebyshev.h)
// summed from 0 over taps 0..3 in order: the scalar lookups' sum, bit for bit. Inactive lanes
// mix zeros. MSM's AVX2 batch (moment_shadow_map.cpp) uses it instead of the taps.
using Mix8x4Fn = void (*)(const MapLookupConsts& c, const Receivers8& r, const PlaneGather& plane,
                          double (*m)[8]);

// Prefetches the two texel rows of each active lane's bilinear footprint in a plane of
// floats_per_texel values per texel (a hint only: no value changes). The batched lookup issues it
// for the next 8 pixels before reconstructing the current ones, so their map lines (the maps are
// larger than the caches at res 1024) arrive while the current batch computes.
using Prefetch8Fn = void (*)(const MapLookupConsts& c, const Receivers8& r,
                             const PlaneGather& plane, int floats_per_texel);

// The pixel loop's result of a batch: mask[k] = active lane ? std::clamp(vis[k], 0, 1) :
// r.mask[k], texels[k] = r.texel[k] (when texels is given), with std::clamp's compare order (a
// NaN stays NaN).
using Merge8Fn = void (*)(const Receivers8& r, const float* vis, float* mask, uint32_t* texels);

// The texel tiles of 8 pixels' bilinear footprints (texel_tiles.cpp's pixel path): per active
// lane its face and the tile columns tx0..tx1 and rows ty0..ty1 (tile edge 2^tile_shift
// texels) of the footprint's clamped texels, from the receivers8 texel coordinates (the same
// operations, so the same texels as bilinear_taps of them), without the receivers' depth and
// slope terms.
struct FootprintTiles8 {
  alignas(32) int32_t face[8], tx0[8], tx1[8], ty0[8], ty1[8], active[8];
};
using FootprintTiles8Fn = void (*)(const MapLookupConsts& c, const float* pos, const float* nrm,
                                   const uint8_t* covered, int tile_shift, FootprintTiles8& out);

// The lookup's kernel family: one table per instruction set (docs/simd.md). The scalar table has
// no batch kernels (nullptr: the callers' scalar loops are the oracle) and the scalar merge8;
// the AVX2 table has them all; AVX-512 runs the AVX2 table (the lookups are bound by their
// gathers' memory reads, which wider lanes do not shorten).
struct LookupKernels {
  Isa isa;  // the instruction set the kernels were compiled for
  Receivers8Fn receivers8;
  Depth1Fn depth1;
  PcfFn pcf;
  Faces8Fn faces8;
  FootprintTiles8Fn footprint_tiles8;
  Bilinear8Fn bilinear8;
  Bilinear8x2Fn bilinear8_interleaved2;
  Bilinear8x2Fn bilinear8_interleaved4;
  Mix8x4Fn bilinear8_mix4;
  Prefetch8Fn prefetch8;
  Merge8Fn merge8;
};
const LookupKernels& lookup_kernels(Isa isa);

}  // namespace shadowlab
