#pragma once
// The hard cases of the scene suite (scenes/scene_suite.h), each built in (no assets):
//   grazing:     a light 0.6 m above one end of a 40 m floor with posts and a fence of 2 cm
//                slats: long projected shadows at 1–6° incidence (aliasing, acne, bias).
//   contact:     a chair on 3 cm legs, touching boxes, a 4 mm wire and a chain-link fence card
//                with an alpha texture, under a light 2 m up: peter-panning, leaks, thin and
//                cut-out occluders.
//   depth_range: a light with a 1 cm near plane over a 2.4 km ground with boxes 1, 10, 100 and
//                1000 m away (far 1800 m): depth precision.
#include "core/scene.h"

namespace shadowlab {

Scene make_grazing_scene();
Scene make_contact_scene();
Scene make_depth_range_scene();

}  // namespace shadowlab
