#pragma once
// The GBuffer's deferred shading attributes: a pixel's shading normal and texture coordinate,
// interpolated over its visible triangle at its position. The camera pass (raster/
// gbuffer_pass.h) does not store them: no technique, reference or metric reads them, only the
// pictures for people (techniques/shading/scene_shading.h, techniques/shading/projector_shading.h), and
// writing them for every pixel cost about a fifth of the pass (docs/performance_history.md).
#include <cstddef>

#include "core/gbuffer.h"
#include "core/math.h"
#include "core/scene.h"

namespace shadowlab {

struct ShadingAttributes {
  vec3 normal{0.0f};  // shading normal, world space, unit length, on the side of geo_normal
  vec2 uv{0.0f};      // texture coordinates (0 when the mesh has none)
};

// Barycentric coordinates (l0, l1, l2), summing to 1, of the point of the triangle (a, b, c)'s
// plane nearest p (p's orthogonal projection), in double; (1/3, 1/3, 1/3) for a degenerate
// triangle.
dvec3 barycentric_of_point(const vec3& p, const vec3& a, const vec3& b, const vec3& c);

// Pixel i's attributes: the GBuffer's own where it has them (has_shading_attributes), else
// from its triangle (mesh_id, prim_id) at its position: the vertex normals interpolated and
// normalized, flipped to the side of geo_normal (the geometric normal where the mesh has no
// normals or they sum to zero); the vertex uvs interpolated. Zero for an uncovered pixel.
ShadingAttributes shading_attributes(const Scene& scene, const GBuffer& g, size_t i);

// Stores every pixel's attributes in g.normal and g.uv (no-op when it has them), for a caller
// that shades one GBuffer several times (a sweep's rows): computed once, not once per picture.
// `scene` must be the one g was rendered from.
void fill_shading_attributes(const Scene& scene, GBuffer& g);

}  // namespace shadowlab
