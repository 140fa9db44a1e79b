#include "raster/tile_binner.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "core/parallel.h"
#include "raster/clip.h"
#include "core/isa.h"
#include "raster/setup_simd.h"
#include "raster/vertex_transform.h"

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
  // Tile coordinates are kept in 16 bits while binning (TileRect below): 4 Mi pixels a side,
  // far beyond any image the tools accept (core/image.h: kMaxImageSide).
  if (frame.tiles_x > 65536 || frame.tiles_y > 65536)
    throw std::invalid_argument("bin_triangles: viewport wider than 2^22 pixels");

  // Whole meshes outside the frustum are skipped; the rest get one transform per vertex. The
  // per-vertex arrays are sized unwritten (DefaultInitAllocator): the parallel transform below
  // writes every entry, and zero-filling them first ran on this thread alone (room1m: 16 MB a
  // face, before any worker starts).
  std::vector<std::vector<vec4, DefaultInitAllocator<vec4>>> clip(meshes.size());
  // Per vertex, see vertex_outcode.
  std::vector<std::vector<uint32_t, DefaultInitAllocator<uint32_t>>> outcode(meshes.size());
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
  const TransformVerticesFn transform = vertex_transform_kernels(process_isa()).transform;
  parallel_for(0, pieces.size(), [&](size_t k) {
    const Piece& pc = pieces[k];
    const vec3* pos = meshes[pc.mesh].positions;
    vec4* out = clip[pc.mesh].data();
    uint32_t* code = outcode[pc.mesh].data();
    if (!paraboloid) {
      transform(view_proj, pos + pc.begin, pc.end - pc.begin, guard_x, guard_y, out + pc.begin,
                code + pc.begin);
      return;
    }
    for (size_t i = pc.begin; i < pc.end; ++i) {
      out[i] = paraboloid_clip(*paraboloid, pos[i]);
      code[i] = vertex_outcode(out[i], guard_x, guard_y);  // once per vertex, not per corner
    }
  });
  const size_t total = first_triangle.back();

  const size_t chunk_count = (total + kChunkTriangles - 1) / kChunkTriangles;
  frame.chunks.resize(chunk_count);
  std::vector<RasterStats> chunk_stats(chunk_count);
  const SetupBatch8Fn setup8 = setup_kernels(process_isa()).batch8;
  parallel_for(0, chunk_count, [&](size_t ci) {
    BinnedChunk& chunk = frame.chunks[ci];
    RasterStats& st = chunk_stats[ci];
    const size_t begin = ci * kChunkTriangles, end = std::min(total, begin + kChunkTriangles);
    // Pass 1: the trivial tests only. The survivors (chunk-local index, kNeedsClip for the
    // clipped ones) size the setup array exactly before any setup is written: growing it by
    // doubling copied ~200-byte records and was 7 % of room1m's cube.
    constexpr uint16_t kNeedsClip = 0x8000;
    static_assert(kChunkTriangles <= kNeedsClip, "a chunk-local index must fit below the flag");
    uint16_t survivors[kChunkTriangles];
    size_t kept = 0, clipped = 0;
    size_t m = size_t(std::upper_bound(first_triangle.begin(), first_triangle.end(), begin) -
                      first_triangle.begin()) - 1;
    const size_t first_mesh = m;
    for (size_t t = begin; t < end; ++t) {
      while (t >= first_triangle[m + 1]) ++m;
      if (mesh_culled[m]) {  // counted above; jump to the mesh's end
        t = std::min(end, first_triangle[m + 1]) - 1;
        continue;
      }
      const uint32_t* idx = meshes[m].indices + 3 * (t - first_triangle[m]);
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
      const bool clip_it = cls == ClipClass::NeedsClip;
      clipped += clip_it;
      survivors[kept++] = uint16_t(t - begin) | (clip_it ? kNeedsClip : 0);
    }
    // A clipped polygon of n vertices gives n - 2 triangles.
    constexpr size_t kMaxClipTriangles = std::size(ClipPolygon{}.v) - 2;
    const size_t most_setups = kept + clipped * (kMaxClipTriangles - 1);
    chunk.setups.reserve(most_setups);

    // Pass 2: set up the survivors in submission order and note each new record's tile
    // rectangle while it is still in L1: the per-tile counts are made here, and the fill below
    // reads the 8-byte rectangles instead of the records (the count and the fill each re-read
    // records that no longer fit in L2).
    struct TileRect {
      uint16_t x0, y0, x1, y1;
    };
    std::vector<TileRect> rects(most_setups);
    size_t noted = 0;
    chunk.offsets.assign(tiles + 1, 0);
    uint32_t* const counts = chunk.offsets.data() + 1;
    const size_t tiles_x = size_t(frame.tiles_x);
    auto note_new_setups = [&] {
      const TriangleSetup* const setups = chunk.setups.data();
      for (const size_t n = chunk.setups.size(); noted < n; ++noted) {
        const TriangleSetup& s = setups[noted];  // bounds are >= 0: clamped to the viewport
        const TileRect r{uint16_t(unsigned(s.min_x) / kTileSize), uint16_t(unsigned(s.min_y) / kTileSize),
                         uint16_t(unsigned(s.max_x) / kTileSize), uint16_t(unsigned(s.max_y) / kTileSize)};
        rects[noted] = r;
        for (size_t ty = r.y0; ty <= r.y1; ++ty)
          for (size_t tx = r.x0; tx <= r.x1; ++tx) ++counts[ty * tiles_x + tx];
      }
    };
    // Triangles that need no clipping are set up 8 at a time where AVX2 or AVX-512 is in use (the
    // same bits as setup_triangle), in submission order: a clipped triangle first flushes the batch.
    SetupBatch8 batch;
    auto flush = [&] {
      if (batch.count == 0) return;
      const size_t at = chunk.setups.size();
      chunk.setups.resize(at + size_t(batch.count));  // unwritten (DefaultInitAllocator)
      const int n = setup8(batch, width, height, cull, chunk.setups.data() + at, st);
      chunk.setups.resize(at + size_t(n));
      batch.count = 0;
      note_new_setups();
    };
    m = first_mesh;
    for (size_t k = 0; k < kept; ++k) {
      const size_t t = begin + (survivors[k] & ~kNeedsClip);
      while (t >= first_triangle[m + 1]) ++m;
      const uint32_t* idx = meshes[m].indices + 3 * (t - first_triangle[m]);
      const vec4& a = clip[m][idx[0]];
      const vec4& b = clip[m][idx[1]];
      const vec4& c = clip[m][idx[2]];
      TriangleSetup s;
      if (!(survivors[k] & kNeedsClip)) {
        if (setup8) {
          const int j = batch.count++;
          const vec4* v[3] = {&a, &b, &c};
          for (int i = 0; i < 3; ++i) {
            batch.x[i][j] = v[i]->x;
            batch.y[i][j] = v[i]->y;
            batch.w[i][j] = v[i]->w;
          }
          batch.triangle[j] = uint32_t(t);
          if (batch.count == 8) flush();
          continue;
        }
        const ClipVertex v0{a, vec3(1, 0, 0)}, v1{b, vec3(0, 1, 0)}, v2{c, vec3(0, 0, 1)};
        if (setup_triangle(v0, v1, v2, uint32_t(t), width, height, cull, s, st)) {
          chunk.setups.push_back(s);
          note_new_setups();
        }
        continue;
      }
      flush();  // the batch's triangles come before this one
      ++st.clipped;
      const ClipPolygon poly = clip_triangle(a, b, c, guard_x, guard_y);
      for (int i = 1; i + 1 < poly.count; ++i)
        if (setup_triangle(poly.v[0], poly.v[i], poly.v[i + 1], uint32_t(t), width, height, cull,
                           s, st))
          chunk.setups.push_back(s);
      note_new_setups();
    }
    flush();
    st.setups = chunk.setups.size();
    // Bin: prefix-sum the counts, then fill, in setup order.
    for (size_t t = 0; t < tiles; ++t) chunk.offsets[t + 1] += chunk.offsets[t];
    chunk.items.resize(chunk.offsets[tiles]);
    std::vector<uint32_t> cursor(chunk.offsets.begin(), chunk.offsets.end() - 1);
    for (uint32_t i = 0; i < noted; ++i) {
      const TileRect r = rects[i];
      for (size_t ty = r.y0; ty <= r.y1; ++ty)
        for (size_t tx = r.x0; tx <= r.x1; ++tx) chunk.items[cursor[ty * tiles_x + tx]++] = i;
    }
  });
  for (const RasterStats& s : chunk_stats) add_stats(frame.stats, s);
  return frame;
}

}  // namespace shadowlab
