#pragma once
// Stage 2 of the light-map pipeline (techniques/pipeline/light_map.h): which faces some pixel's lookup
// touches, so that only those are rendered. The answer is the exact set of faces of the
// covered, light-facing pixels' lookups (and, for cross-face PCF, of their taps); every path
// below gives that same set (docs/techniques/pipeline.md).
#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/pipeline/map_params.h"

namespace shadowlab {

// Faces the lookups of the covered, light-facing pixels touch. Without `looked_up` it first
// walks a sparse sample of the pixels and stops there when that already needs every face; then,
// when the GBuffer has block bounds, it decides whole 16×16 blocks from them (box_single_face;
// box_misses_faces for a block across faces already known) and walks only the pixels of the
// blocks it cannot decide. With `looked_up`, every pixel is
// walked and `looked_up` receives the number of such pixels.
std::vector<bool> faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                               const MapParams& p, size_t* looked_up = nullptr);

// The face f such that every point within `reach` metres of the box [lo, hi] (world space) has
// face_of(point − light) == f and, when cross_pcf > 1, its whole cross_pcf × cross_pcf PCF
// footprint inside f's image (pcf_taps_inside), with a margin that covers float rounding (a
// relative 1e-5 of the coordinates' magnitude, and one texel for the footprint); −1 when the box
// cannot be decided so (it straddles a face boundary or the light, is not finite, or the layout
// is the projector's, whose single face needs no decision).
//
// Why a box can be decided from its corners alone: each face owns a convex cone of directions,
// an intersection of half-spaces a·d >= 0 through the light (cube: forward ± right and forward ±
// up; tetrahedron: n_f − n_j; dual paraboloid: ±forward), and the footprint-inside condition on
// a gnomonic face is four more such half-spaces. The minimum of a·d over a box is
// a·centre − Σ|a_i|·half_i, so one test per half-space decides every point of the box.
int box_single_face(const FaceLayout& layout, const vec3& light, const vec3& lo, const vec3& hi,
                    float reach, int cross_pcf);

// True when no point within `reach` metres of the box maps to a face in the bit set `faces`
// (bit f: face f): the box lies outside each such face's cone by the margin box_single_face
// uses. A box that straddles faces all known to be needed is then decided without a walk.
// For cross-face PCF, grow `reach` by pcf_tap_reach so that the taps are held too. False for
// the projector's layout and for a box that is not finite.
bool box_misses_faces(const FaceLayout& layout, const vec3& light, const vec3& lo,
                      const vec3& hi, float reach, uint32_t faces);

// How far (metres) from a lookup point of the box, itself within `reach` of the box, the points
// whose directions are those of its cross-seam PCF taps (pcf × pcf, for_each_pcf_tap) can lie:
// the footprint's half-width in plane texels × the largest plane texel × the distance from the
// light; 0 for pcf <= 1. A box grown by reach + this holds every tap's direction.
float pcf_tap_reach(const FaceLayout& layout, int pcf, const BlockBounds& box, const vec3& light,
                    float reach);

// How far (metres) the normal offset may move a lookup point of the block's box: at most
// normal × plane texel × distance (techniques/lookup/normal_offset.h), with 1 % more for its rounding;
// 0 without normal offset.
inline float normal_offset_reach(const MapParams& p, float plane_texel, const BlockBounds& box,
                                 const vec3& light) {
  if (!(p.normal > 0.0f)) return 0.0f;
  const vec3 far_corner = glm::max(glm::abs(box.lo - light), glm::abs(box.hi - light));
  return 1.01f * p.normal * plane_texel * glm::length(far_corner);
}

}  // namespace shadowlab
