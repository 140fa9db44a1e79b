#pragma once
// How many texels of a face an angle seen from the light covers at a point of the face: PCSS
// turns its angles (the blocker search's, the penumbra's) into texel radii with it.
#include <cmath>

#include "techniques/pipeline/light_faces.h"

namespace shadowlab {

// Texels per radian at continuous texel coordinates st of face f. A gnomonic face (cube,
// tetrahedral, projector) has per_plane · ρ, ρ = √(1 + u² + v²) the distance from the light to
// the point (u, v) of the unit image plane: its isotropic, tangential scale (radially it
// stretches by another ρ, ignored). The paraboloid map is conformal, with 2/(1 + u² + v²)
// radians per plane unit: per_plane · (1 + u² + v²) / 2 in every direction.
inline float pcss_texels_per_radian(const LightFace& f, vec2 st) {
  const float per_plane = float(f.width) / (f.right_edge - f.left);  // texels per plane unit
  const float u = f.left + st.x / per_plane;
  const float v = f.top - st.y * (f.top - f.bottom) / float(f.height);
  return f.paraboloid ? per_plane * 0.5f * (1.0f + u * u + v * v)
                      : per_plane * std::sqrt(1.0f + u * u + v * v);
}

}  // namespace shadowlab
