#pragma once
// The camera pass: rasterizes the scene from its camera into a GBuffer (core/gbuffer.h).
// Visibility is resolved first (triangle id and barycentrics per pixel); attributes are then
// computed once per covered pixel, so overdraw costs no attribute work.
#include "core/gbuffer.h"
#include "core/scene.h"
#include "raster/raster_types.h"

namespace shadowlab {

// Renders scene.camera's view at scene.camera.width × height with no face culling.
// Geometric and shading normals are flipped to face the camera (two-sided surfaces).
GBuffer render_gbuffer(const Scene& scene, RasterStats* stats = nullptr);
// Same, into an existing GBuffer whose storage is reused (timing loops: no page faults).
// allow_simd = false forces the scalar resolve, the oracle of the AVX2 one (tests).
void render_gbuffer(const Scene& scene, GBuffer& out, RasterStats* stats = nullptr,
                    bool allow_simd = true);

}  // namespace shadowlab
