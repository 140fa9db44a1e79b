#include "raster/tile_binner.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "raster/clip.h"
#include "raster/setup_simd.h"

namespace shadowlab {
namespace {

// Triangles per chunk: large enough to amortise the per-chunk tile tables, small enough to
// balance two or more threads.
constexpr size_t kChunkTriangles = 8192;

}  // namespace

bool box_outside_frustum(const vec3& lo, const vec3& hi, const mat4& view_proj) {
  vec4 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] = view_proj * vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
  // Planes as (sign, axis): x <= w, -x <= w, y <= w, -y <= w, and near: -z <= w.
  auto all_out = [&](auto dist) {
    for (const vec4& p : c)
      if (dist(p) >= 0.0f) return false;
    return true;
  };
  return all_out([](const vec4& p) { return p.w - p.x; }) ||
         all_out([](const vec4& p) { return p.w + p.x; }) ||
         all_out([](const vec4& p) { return p.w - p.y; }) ||
         all_out([](const vec4& p) { return p.w + p.y; }) ||
         all_out([](const vec4& p) { return p.w + p.z; });
}

BinnedFrame bin_triangles(const std::vector<MeshView>& meshes, const mat4& view_proj,
                          CullMode cull, int width, int height,
                          const ParaboloidProjection* paraboloid) {
  BinnedFrame frame;
  frame.width = width;
  frame.height = height;
  frame.tiles_x = (width + kTileSize - 1) / kTileSize;
  frame.tiles_y = (height + kTileSize - 1) / kTileSize;
  const size_t tiles = size_t(frame.tiles_x) * size_t(frame.tiles_y);
  if (width <= 0 || height <= 0) return frame;

  // Whole meshes outside the frustum are skipped; the rest get one transform per vertex.
  std::vector<std::vector<vec4>> clip(meshes.size());
  std::vector<std::vector<uint32_t>> outcode(meshes.size());  // per vertex, see vertex_outcode
  std::vector<size_t> first_triangle(meshes.size() + 1, 0);
  std::vector<uint8_t> mesh_culled(meshes.size(), 0);
  for (size_t m = 0; m < meshes.size(); ++m) {
    first_triangle[m + 1] = first_triangle[m] + meshes[m].triangle_count;
    const MeshView& mesh = meshes[m];
    if (mesh.skip) {
      mesh_culled[m] = 1;
      continue;
    }
    if (!paraboloid && mesh.has_bounds && box_outside_frustum(mesh.lo, mesh.hi, view_proj)) {
      mesh_culled[m] = 1;
      frame.stats.triangles_in += mesh.triangle_count;
      frame.stats.culled_frustum += mesh.triangle_count;
      continue;
    }
    clip[m].resize(meshes[m].vertex_count);
    outcode[m].resize(meshes[m].vertex_count);
  }
  const float guard_x = float(1.0 + 2.0 * kGuardBandPixels / double(width));
  const float guard_y = float(1.0 + 2.0 * kGuardBandPixels / double(height));
  // One parallel loop over (mesh, vertex range) pieces: scenes of many small meshes would
  // otherwise run one tiny, effectively serial loop per mesh.
  struct Piece {
    size_t mesh, begin, end;
  };
  std::vector<Piece> pieces;
  constexpr size_t kVertexGrain = 8192;
  for (size_t m = 0; m < meshes.size(); ++m)
    if (!mesh_culled[m])
      for (size_t b = 0; b < meshes[m].vertex_count; b += kVertexGrain)
        pieces.push_back({m, b, std::min(meshes[m].vertex_count, b + kVertexGrain)});
  parallel_for(0, pieces.size(), [&](size_t k) {
    const Piece& pc = pieces[k];
    const vec3* pos = meshes[pc.mesh].positions;
    vec4* out = clip[pc.mesh].data();
    uint32_t* code = outcode[pc.mesh].data();
    for (size_t i = pc.begin; i < pc.end; ++i) {
      out[i] = paraboloid ? paraboloid_clip(*paraboloid, pos[i]) : view_proj * vec4(pos[i], 1.0f);
      code[i] = vertex_outcode(out[i], guard_x, guard_y);  // once per vertex, not per corner
    }
  });
  const size_t total = first_triangle.back();

  const size_t chunk_count = (total + kChunkTriangles - 1) / kChunkTriangles;
  frame.chunks.resize(chunk_count);
  std::vector<RasterStats> chunk_stats(chunk_count);
  // Triangles that need no clipping are set up 8 at a time where AVX2 or AVX-512 is in use (the
  // same bits as setup_triangle), in submission order: a clipped triangle first flushes the batch.
  const SetupBatch8Fn setup8 = setup_batch8_simd();
  parallel_for(0, chunk_count, [&](size_t ci) {
    BinnedChunk& chunk = frame.chunks[ci];
    RasterStats& st = chunk_stats[ci];
    SetupBatch8 batch;
    auto flush = [&] {
      if (batch.count == 0) return;
      const size_t at = chunk.setups.size();
      chunk.setups.resize(at + size_t(batch.count));  // unwritten (DefaultInitAllocator)
      const int n = setup8(batch, width, height, cull, chunk.setups.data() + at, st);
      chunk.setups.resize(at + size_t(n));
      batch.count = 0;
    };
    const size_t begin = ci * kChunkTriangles, end = std::min(total, begin + kChunkTriangles);
    // A quarter of the chunk: most views keep fewer (frustum culling), and a full-size reserve
    // of ~200-byte setups would page-fault far more memory than it saves in regrowth copies.
    chunk.setups.reserve((end - begin) / 4 + 16);
    size_t m = size_t(std::upper_bound(first_triangle.begin(), first_triangle.end(), begin) -
                      first_triangle.begin()) - 1;
    for (size_t t = begin; t < end; ++t) {
      while (t >= first_triangle[m + 1]) ++m;
      if (mesh_culled[m]) {  // counted above; jump to the mesh's end
        t = std::min(end, first_triangle[m + 1]) - 1;
        continue;
      }
      const size_t local = t - first_triangle[m];
      const uint32_t* idx = meshes[m].indices + 3 * local;
      const vec4& a = clip[m][idx[0]];
      const vec4& b = clip[m][idx[1]];
      const vec4& c = clip[m][idx[2]];
      ++st.triangles_in;
      const uint32_t* oc = outcode[m].data();
      const uint32_t ca = oc[idx[0]], cb = oc[idx[1]], cc = oc[idx[2]];
      if ((ca | cb | cc) & kOutNonFinite) {
        ++st.dropped_nonfinite;
        continue;
      }
      const ClipClass cls = classify_outcodes(ca, cb, cc);
      if (cls == ClipClass::Outside) {
        ++st.culled_frustum;
        continue;
      }
      TriangleSetup s;
      if (cls == ClipClass::Inside && setup8) {
        const int k = batch.count++;
        const vec4* v[3] = {&a, &b, &c};
        for (int i = 0; i < 3; ++i) {
          batch.x[i][k] = v[i]->x;
          batch.y[i][k] = v[i]->y;
          batch.w[i][k] = v[i]->w;
        }
        batch.triangle[k] = uint32_t(t);
        if (batch.count == 8) flush();
        continue;
      }
      if (cls == ClipClass::Inside) {
        const ClipVertex v0{a, vec3(1, 0, 0)}, v1{b, vec3(0, 1, 0)}, v2{c, vec3(0, 0, 1)};
        if (setup_triangle(v0, v1, v2, uint32_t(t), width, height, cull, s, st))
          chunk.setups.push_back(s);
        continue;
      }
      flush();  // the batch's triangles come before this one
      ++st.clipped;
      const ClipPolygon poly = clip_triangle(a, b, c, guard_x, guard_y);
      for (int i = 1; i + 1 < poly.count; ++i)
        if (setup_triangle(poly.v[0], poly.v[i], poly.v[i + 1], uint32_t(t), width, height, cull,
                           s, st))
          chunk.setups.push_back(s);
    }
    flush();
    st.setups = chunk.setups.size();
    // Bin: count per tile, prefix-sum, fill — in setup order.
    chunk.offsets.assign(tiles + 1, 0);
    for (const TriangleSetup& s : chunk.setups)
      for (int ty = s.min_y / kTileSize; ty <= s.max_y / kTileSize; ++ty)
        for (int tx = s.min_x / kTileSize; tx <= s.max_x / kTileSize; ++tx)
          ++chunk.offsets[size_t(ty) * frame.tiles_x + tx + 1];
    for (size_t t = 0; t < tiles; ++t) chunk.offsets[t + 1] += chunk.offsets[t];
    chunk.items.resize(chunk.offsets[tiles]);
    std::vector<uint32_t> cursor(chunk.offsets.begin(), chunk.offsets.end() - 1);
    for (uint32_t i = 0; i < chunk.setups.size(); ++i) {
      const TriangleSetup& s = chunk.setups[i];
      for (int ty = s.min_y / kTileSize; ty <= s.max_y / kTileSize; ++ty)
        for (int tx = s.min_x / kTileSize; tx <= s.max_x / kTileSize; ++tx)
          chunk.items[cursor[size_t(ty) * frame.tiles_x + tx]++] = i;
    }
  });
  for (const RasterStats& s : chunk_stats) add_stats(frame.stats, s);
  return frame;
}

}  // namespace shadowlab
