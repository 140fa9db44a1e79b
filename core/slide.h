#pragma once
// Slides of the slide projector (Dowling): the image a projector light casts. A slide is always
// an RGB image of linear values in [0, 1] (procedural slides are baked), looked up with one
// bilinear filter at slide coordinates st: s right, t down, (0, 0) = top-left corner of the
// image, (1, 1) = bottom-right; clamp to edge.
//
// Slide specs (the --slide flag):
//   spot                  the cross-section of a spotlight beam: 1 inside radius 0.6 of the
//                         slide's inscribed circle, a smoothstep falloff to 0 at radius 1.0,
//                         0 in the corners (r = distance from the centre / half the side)
//   grid:amp=A,freq=F     the spot times the lattice m(s)·m(t) with
//                         m(x) = 1 − A·(1 − cos(2π·F·(x − ½)))/2: F cycles across the slide in
//                         x and y, A ∈ [0, 1] the modulation depth (F = 0: the plain spot; A = 1:
//                         the lattice lines are fully dark; cos centred so the beam's axis is lit)
//   spot:res=N, grid:...,res=N   bake size (N × N texels, default 512, 8..4096)
//   PATH.png|.jpg|.exr    an image file: 8-bit files are sRGB-decoded to linear, EXR is linear
#include <string>

#include "core/image.h"
#include "core/math.h"

namespace shadowlab {

struct Slide {
  std::string name;  // the spec it came from (for reports and cache keys)
  ImageF rgb;        // 3 planar channels, linear, [0, 1] (files may exceed 1 for EXR)
};

// Builds the slide a spec names; throws InputError(flag, reason) for an unknown name or key, a
// value out of range, or (naming the file) an unreadable image.
Slide make_slide(const std::string& spec, const std::string& flag);

// Procedural values at slide coordinates st (exact; the baked images sample these at texel
// centres).
float spot_profile(vec2 st);
float grid_modulation(vec2 st, float amp, float freq);

// Bilinear lookup at st (see the top of this file); texel (x, y) has its centre at
// ((x + 0.5)/W, (y + 0.5)/H).
vec3 sample_slide(const ImageF& rgb, vec2 st);

}  // namespace shadowlab
