#include "techniques/pipeline/paraboloid_tess.h"

#include <algorithm>

#include "core/parallel.h"

namespace shadowlab {

// tess=N on the paraboloid layout: every edge whose image in the face is longer than N texels
// is split at its world-space midpoint, and each triangle is cut along its split edges (1, 2 or 3
// of them: 2, 3 or 4 pieces), recursively, so the image's straight edges follow the true curves.
// Whether an edge splits depends on that edge alone (its two endpoints, in either order: the
// midpoint 0.5·(a + b) and the image length are symmetric), so two triangles sharing an edge
// split it alike and no crack opens between them (a longest-edge rule, decided per triangle,
// left T-junctions whose cracks leaked light on room100k). Edges with both ends behind the
// face's rim margin never split (the clip removes them; their images blow up towards the
// antipode). Splitting is adaptive (a far piece's image is small and stops early; a 2 km
// triangle under the light needs ~30 levels at its nadir); as a guard on work, 48 levels and
// 2^20 pieces per input triangle (beyond them pieces are kept as they are).
void tessellate(const MeshView& m, const ParaboloidProjection& pp, float texels_per_unit,
                float max_texels, Tessellated& out) {
  auto image = [&](const vec3& p) { return paraboloid_point(pp, p - pp.centre) * texels_per_unit; };
  auto behind = [&](const vec3& p) {
    const vec3 d = p - pp.centre;
    return glm::dot(d, pp.forward) < -pp.behind * glm::length(d);
  };
  auto splits = [&](const vec3& p, const vec3& q) {
    if (behind(p) && behind(q)) return false;
    return glm::length(image(q) - image(p)) > max_texels;
  };
  struct Tri {
    vec3 v[3];
    int depth;
  };
  // Chunks of triangles in parallel, each into its own list, joined in triangle order (the
  // output does not depend on the thread count).
  constexpr size_t kGrain = 64;
  const size_t chunks = (m.triangle_count + kGrain - 1) / kGrain;
  std::vector<Tessellated> parts(chunks);
  parallel_for(0, chunks, [&](size_t ci) {
    Tessellated& part = parts[ci];
    std::vector<Tri> stack;
    for (size_t t = ci * kGrain; t < std::min(m.triangle_count, (ci + 1) * kGrain); ++t) {
      const uint32_t* idx = m.indices + 3 * t;
      stack.push_back({{m.positions[idx[0]], m.positions[idx[1]], m.positions[idx[2]]}, 0});
      size_t pieces = 1;
      while (!stack.empty()) {
        const Tri tri = stack.back();
        stack.pop_back();
        // Edge e runs from v[e] to v[(e + 1) % 3].
        bool split[3] = {false, false, false};
        int count = 0;
        if (tri.depth < 48 && pieces < (size_t(1) << 20))
          for (int e = 0; e < 3; ++e) count += split[e] = splits(tri.v[e], tri.v[(e + 1) % 3]);
        if (count == 0) {
          for (const vec3& v : tri.v) part.positions.push_back(v);
          continue;
        }
        pieces += size_t(count);
        vec3 mid[3];
        for (int e = 0; e < 3; ++e)
          if (split[e]) mid[e] = 0.5f * (tri.v[e] + tri.v[(e + 1) % 3]);
        const int d = tri.depth + 1;
        if (count == 3) {
          stack.push_back({{tri.v[0], mid[0], mid[2]}, d});
          stack.push_back({{mid[0], tri.v[1], mid[1]}, d});
          stack.push_back({{mid[2], mid[1], tri.v[2]}, d});
          stack.push_back({{mid[0], mid[1], mid[2]}, d});
          continue;
        }
        // Rotate so that edge 0 is the (first) split one; windings are kept.
        int r = 0;
        if (count == 1) {
          while (!split[r]) ++r;
        } else {  // two: start at the split edge followed by the other split one
          while (!(split[r] && split[(r + 1) % 3])) ++r;
        }
        const vec3 a = tri.v[r], b = tri.v[(r + 1) % 3], c = tri.v[(r + 2) % 3];
        const vec3 mab = mid[r];
        if (count == 1) {
          stack.push_back({{a, mab, c}, d});
          stack.push_back({{mab, b, c}, d});
        } else {
          const vec3 mbc = mid[(r + 1) % 3];
          stack.push_back({{mab, b, mbc}, d});
          stack.push_back({{a, mab, mbc}, d});
          stack.push_back({{a, mbc, c}, d});
        }
      }
    }
  });
  for (const Tessellated& part : parts)
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
  out.indices.resize(out.positions.size());
  for (size_t i = 0; i < out.indices.size(); ++i) out.indices[i] = uint32_t(i);
}

}  // namespace shadowlab
