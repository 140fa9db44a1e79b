#include "raster/pipeline.h"

#include <algorithm>

#include "core/parallel.h"

namespace shadowlab {

namespace {

// The bounds of positions [b, e): lo and hi, component-wise.
void bounds_of(const vec3* p, size_t b, size_t e, vec3& lo, vec3& hi) {
  lo = hi = p[b];
  for (size_t i = b + 1; i < e; ++i) {
    lo = glm::min(lo, p[i]);
    hi = glm::max(hi, p[i]);
  }
}

}  // namespace

std::vector<MeshView> scene_mesh_views(const Scene& scene) {
  // Bounds are computed here, once per call: callers rendering several views (cube faces)
  // build the views once and pass them to every rasterize(). One parallel loop over (mesh,
  // position range) pieces (room1m's bounds on one thread were ~1.6 % of its 2-thread cube, and
  // its meshes are many and small); min and max are exact, so the pieces' order cannot change
  // them.
  constexpr size_t kGrain = 65536;
  struct Piece {
    size_t mesh, begin, end;
    vec3 lo, hi;
  };
  std::vector<Piece> pieces;
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t b = 0, n = scene.meshes[m].positions.size(); b < n; b += kGrain)
      pieces.push_back({m, b, std::min(n, b + kGrain), vec3(0.0f), vec3(0.0f)});
  parallel_for(0, pieces.size(), [&](size_t k) {
    Piece& pc = pieces[k];
    bounds_of(scene.meshes[pc.mesh].positions.data(), pc.begin, pc.end, pc.lo, pc.hi);
  });
  std::vector<MeshView> views;
  views.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    views.push_back({m.positions.data(), m.positions.size(), m.indices.data(), m.triangle_count()});
    views.back().has_bounds = !m.positions.empty();
  }
  // A NaN/Inf vertex must only drop its own triangles (counted in the binner), never cull the
  // whole mesh through a NaN bound. A piece whose first position is NaN has NaN bounds
  // (glm::min keeps its first argument against a NaN), which the combine would skip with the
  // piece's other positions: any non-finite piece drops its mesh's bounds instead, as a NaN
  // first position always did. Bounds only let the binner cull; without them nothing is culled
  // wrongly.
  for (const Piece& pc : pieces) {
    MeshView& v = views[pc.mesh];
    v.lo = pc.begin == 0 ? pc.lo : glm::min(v.lo, pc.lo);
    v.hi = pc.begin == 0 ? pc.hi : glm::max(v.hi, pc.hi);
    v.has_bounds = v.has_bounds && is_finite(pc.lo) && is_finite(pc.hi);
  }
  return views;
}

std::vector<uint32_t> scene_first_triangles(const Scene& scene) {
  std::vector<uint32_t> first(scene.meshes.size() + 1, 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    first[m + 1] = first[m] + uint32_t(scene.meshes[m].triangle_count());
  return first;
}

}  // namespace shadowlab
