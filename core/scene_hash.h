#pragma once
// Content hash of a scene, for provenance (docs/provenance.md): two runs with the same hash
// rendered the same geometry, materials, textures, light, projector and camera.
#include <string>

#include "core/scene.h"

namespace shadowlab {

// 16 lower-case hex digits: FNV-1a 64 (core/hash.h) over every mesh (positions, normals, uvs,
// indices, material), material (albedo, textures, cutoff, colour factor), texture (size and
// texels), the light, the projector (pose and slide), the camera and the seed; floats by their
// bits. Names are left out: renaming a scene does not change what it renders.
std::string scene_hash(const Scene& scene);

}  // namespace shadowlab
