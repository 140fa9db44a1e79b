#pragma once
// A stiff hand-built case for the stability rows and the face-seam tests
// (lab/stability_cases.h): a scene with a GBuffer of receivers placed by hand, no camera pass.
#include "core/gbuffer.h"
#include "core/scene.h"

namespace shadowlab {

// A closed 4 m box around an off-centre light, with hand-placed receivers on its walls in a
// dense Fibonacci set of 90k directions (0.7° apart), so that every cube and tetrahedron face
// boundary and corner is crossed many times. Points within 0.4 m of the box's own concave
// edges are left out (covered = 0): there a filtered map darkens legitimately, because the
// adjacent wall is nearer than the receiver's plane. Every receiver is lit.
struct BoxRoom {
  Scene scene;
  GBuffer g;
};
BoxRoom make_box_room();

}  // namespace shadowlab
