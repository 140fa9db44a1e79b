#include "techniques/pipeline/texel_tiles.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "techniques/pipeline/faces_needed.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {

void tile_spans(const FaceTiles* tiles, int band, int w, std::vector<TexelSpan>& spans) {
  spans.clear();
  if (!tiles || tiles->every()) {
    spans.push_back({0, w});
    return;
  }
  const uint8_t* row = tiles->need.data() + size_t(band) * size_t(tiles->tiles_x);
  for (int tx = 0; tx < tiles->tiles_x;) {
    if (!row[tx]) {
      ++tx;
      continue;
    }
    const int start = tx;
    while (tx < tiles->tiles_x && row[tx]) ++tx;
    spans.push_back({start * kTexelTile, std::min(w, tx * kTexelTile)});
  }
}

uint64_t tile_texels(const FaceTiles* tiles, int w, int h) {
  if (!tiles || tiles->every()) return uint64_t(w) * uint64_t(h);
  uint64_t n = 0;
  for (int ty = 0; ty < tiles->tiles_y; ++ty) {
    const uint64_t rows = uint64_t(std::min(h, (ty + 1) * kTexelTile) - ty * kTexelTile);
    for (int tx = 0; tx < tiles->tiles_x; ++tx)
      if (tiles->need[size_t(ty) * size_t(tiles->tiles_x) + size_t(tx)])
        n += rows * uint64_t(std::min(w, (tx + 1) * kTexelTile) - tx * kTexelTile);
  }
  return n;
}

namespace {

// Tiles for every face of the layout, all unmarked.
std::vector<FaceTiles> empty_tiles(const FaceLayout& layout) {
  std::vector<FaceTiles> out(layout.faces.size());
  for (size_t f = 0; f < out.size(); ++f) {
    const LightFace& lf = layout.faces[f];
    out[f].tiles_x = (lf.width + kTexelTile - 1) / kTexelTile;
    out[f].tiles_y = (lf.height + kTexelTile - 1) / kTexelTile;
    out[f].need.assign(size_t(out[f].tiles_x) * size_t(out[f].tiles_y), 0);
  }
  return out;
}

// Faces not in `faces` get no tiles (a block's hull may reach a face no pixel looks up).
void drop_unneeded(std::vector<FaceTiles>& tiles, const std::vector<bool>& faces) {
  for (size_t f = 0; f < tiles.size(); ++f)
    if (f >= faces.size() || !faces[f]) std::fill(tiles[f].need.begin(), tiles[f].need.end(), 0);
}

// Marks texels [x0, x1] × [y0, y1] (inclusive, inside the face) of face f. Threads mark the same
// bytes concurrently, so through relaxed atomic stores; the result (a union) is read after the
// parallel loop has joined.
void mark_tiles(std::vector<FaceTiles>& tiles, int f, int tx0, int tx1, int ty0, int ty1) {
  FaceTiles& t = tiles[size_t(f)];
  if (t.every()) return;
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) {
      std::atomic_ref<uint8_t> cell(t.need[size_t(ty) * size_t(t.tiles_x) + size_t(tx)]);
      if (!cell.load(std::memory_order_relaxed)) cell.store(1, std::memory_order_relaxed);
    }
}

void mark_texels(std::vector<FaceTiles>& tiles, int f, int x0, int x1, int y0, int y1) {
  mark_tiles(tiles, f, x0 / kTexelTile, x1 / kTexelTile, y0 / kTexelTile, y1 / kTexelTile);
}

// Inclusive texel bounds on one face; empty unless set.
struct TexelRect {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
  uint64_t area() const { return empty() ? 0 : uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1); }
};

// A layout has at most 6 faces (the cube's).
constexpr int kMaxFaces = 6;

struct PixelMarker {
  const Scene& scene;
  const GBuffer& g;
  const FaceLayout& layout;
  const MapParams& p;
  std::vector<FaceTiles>& tiles;
  // The lookups' AVX2 receivers' texel coordinates, as footprint tiles (no normal offset).
  FootprintTiles8Fn tiles8 = nullptr;
  MapLookupConsts consts;
  ProjectorFrame frame;
  float reach = 0.0f, inv_far = 0.0f;

  PixelMarker(const Scene& s, const GBuffer& gb, const FaceLayout& l, const MapParams& mp,
              std::vector<FaceTiles>& t)
      : scene(s), g(gb), layout(l), p(mp), tiles(t) {
    tiles8 = p.normal <= 0.0f ? lookup_kernels(process_isa()).footprint_tiles8 : nullptr;
    if (tiles8) consts = map_lookup_consts(scene, layout, p, {});
    if (layout.kind == FaceLayoutKind::Projector) frame = projector_frame(scene.projector);
    reach = map_reach(p);
    inv_far = 1.0f / scene.light.far;
  }

  // fn(face, tx0, tx1, ty0, ty1) for each looked-up pixel of [b, e): the tiles of the bilinear
  // footprint its lookup reads (lookup_faces' rules: covered, facing the light, inside the
  // projector; bilinear_taps' clamped texels of the receiver's texel coordinates), 8 pixels at a
  // time by footprint_tiles8 (the receivers' face and texel-coordinate operations without their
  // depth and slope terms: the tile pass took 18 % less on room100k than through the whole
  // receivers, docs/performance_history.md), the rest from make_receiver.
  template <class Fn>
  void footprints(size_t b, size_t e, const Fn& fn) const {
    static_assert(kTexelTile == 32, "footprint_tiles8 shifts by 5");
    size_t i = b;
    if (tiles8)
      for (; i + 8 <= e; i += 8) {
        FootprintTiles8 t;
        tiles8(consts, &g.position[i].x, &g.geo_normal[i].x, &g.covered[i], 5, t);
        for (int k = 0; k < 8; ++k)
          if (t.active[k]) fn(t.face[k], t.tx0[k], t.tx1[k], t.ty0[k], t.ty1[k]);
      }
    const vec3 L = scene.light.position;
    for (; i < e; ++i) {
      if (!g.covered[i] || !faces_light(g, i, L)) continue;
      vec2 slide_st;
      if (layout.kind == FaceLayoutKind::Projector &&
          !projector_slide_coords(frame, L, g.position[i], slide_st))
        continue;
      const Receiver r =
          make_receiver(layout, scene.light, p, reach, inv_far, g.position[i], g.geo_normal[i]);
      const LightFace& lf = layout.faces[size_t(r.face)];
      const Bilinear t = bilinear_taps(r.st, lf.width, lf.height);
      fn(r.face, t.x0 / kTexelTile, t.x1 / kTexelTile, t.y0 / kTexelTile, t.y1 / kTexelTile);
    }
  }

  // Every pixel's own footprint marked, skipping a pixel whose tiles are its predecessor's.
  void mark_each(size_t b, size_t e) const {
    int last[5] = {-1, 0, 0, 0, 0};
    footprints(b, e, [&](int f, int tx0, int tx1, int ty0, int ty1) {
      const int cur[5] = {f, tx0, tx1, ty0, ty1};
      if (std::equal(cur, cur + 5, last)) return;
      std::copy(cur, cur + 5, last);
      mark_tiles(tiles, f, tx0, tx1, ty0, ty1);
    });
  }
};

// How a box's corners lie against a face's plane through the light.
enum class Side { Front, Behind, Across };

// Face f's texels read by lookups at points of the box [lo, hi] (metres) whose texel
// coordinates lie in [s_min, s_max] × [t_min, t_max], into `rect` when every corner is in front
// of the face (Front): the face's gnomonic image of the box is then the convex hull of the
// corners' images, so each point's texel coordinates lie within the corners' bounds, up to the
// per-pixel path's float rounding (~1e-3 texel at 1024 texels), which one texel of margin on
// each side covers. `rect` stays empty for Behind (no point of the box projects onto the face)
// and Across.
Side hull_rect(const FaceLayout& layout, const vec3& light, int f, const glm::dvec3& lo,
               const glm::dvec3& hi, double s_min, double s_max, double t_min, double t_max,
               TexelRect& rect) {
  const LightFace& lf = layout.faces[size_t(f)];
  const glm::dvec3 L(light), fwd(lf.forward), right(lf.right), up(lf.up);
  const double su = double(lf.width) / (double(lf.right_edge) - double(lf.left));
  const double sv = double(lf.height) / (double(lf.top) - double(lf.bottom));
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo, t_lo = s_lo, t_hi = -s_lo;
  int front = 0, behind = 0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 d =
        glm::dvec3((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z) - L;
    const double z = glm::dot(d, fwd);
    if (z <= 0.0) ++behind;
    if (!(z > 1e-9 * (std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z)))) continue;
    ++front;
    const double inv_z = 1.0 / z;
    const double s = (glm::dot(d, right) * inv_z - double(lf.left)) * su;
    const double t = (double(lf.top) - glm::dot(d, up) * inv_z) * sv;
    s_lo = std::min(s_lo, s);
    s_hi = std::max(s_hi, s);
    t_lo = std::min(t_lo, t);
    t_hi = std::max(t_hi, t);
  }
  if (behind == 8) return Side::Behind;
  if (front < 8 ||
      !(std::isfinite(s_lo) && std::isfinite(s_hi) && std::isfinite(t_lo) && std::isfinite(t_hi)))
    return Side::Across;
  // The clip keeps one texel beyond the owned region: a receiver exactly on a face boundary may
  // look either face up (face_of's ties and the float extents of the faces put it within a few
  // 1e-6 texel of the edge on either side).
  s_lo = std::max(s_lo, s_min - 1.0);
  s_hi = std::min(s_hi, s_max + 1.0);
  t_lo = std::max(t_lo, t_min - 1.0);
  t_hi = std::min(t_hi, t_max + 1.0);
  // bilinear_taps reads floor(st − ½) and the next texel; one texel more each side for rounding.
  auto texel = [](double c, int n) {
    return int(std::clamp(std::floor(c - 0.5), -1.0, double(n)));
  };
  const int x0 = std::max(0, texel(s_lo, lf.width) - 1);
  const int x1 = std::min(lf.width - 1, texel(s_hi, lf.width) + 2);
  const int y0 = std::max(0, texel(t_lo, lf.height) - 1);
  const int y1 = std::min(lf.height - 1, texel(t_hi, lf.height) + 2);
  if (s_lo <= s_hi && t_lo <= t_hi && x0 <= x1 && y0 <= y1) rect = {x0, x1, y0, y1};
  return Side::Front;
}

// True when no point of the box [lo, hi] (metres, light at L) lies in face f's cone of
// directions, clearly (by more than the per-pixel path's rounding): the box is wholly
// outside one of the half-spaces a·d >= 0 through the light whose intersection the cone is (cube:
// forward ± right, forward ± up; tetrahedron: n_f − n_j), whose maximum over the box is
// a·centre + Σ|a_i|·half_i. Such a face owns none of the block's pixels, whatever its plane does.
bool box_outside_face(const FaceLayout& layout, int f, const glm::dvec3& lo, const glm::dvec3& hi,
                      const vec3& light) {
  const glm::dvec3 centre = 0.5 * (lo + hi) - glm::dvec3(light), half = 0.5 * (hi - lo);
  // The per-pixel path rounds p − L relative to the coordinates' magnitude, not to the distance
  // from the light: box_single_face's margin, 1e-5 of the largest coordinate.
  const double eps = 1e-5 * (std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z),
                                       std::fabs(hi.x), std::fabs(hi.y), std::fabs(hi.z)}) +
                             std::max({std::fabs(light.x), std::fabs(light.y),
                                       std::fabs(light.z)}));
  auto outside = [&](const glm::dvec3& a) {
    return glm::dot(a, centre) + glm::dot(glm::abs(a), half) < -eps * (std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z));
  };
  const LightFace& lf = layout.faces[size_t(f)];
  const glm::dvec3 fwd(lf.forward), right(lf.right), up(lf.up);
  switch (layout.kind) {
    case FaceLayoutKind::Cube:
      return outside(fwd + right) || outside(fwd - right) || outside(fwd + up) || outside(fwd - up);
    case FaceLayoutKind::Tetrahedron:
      for (int j = 0; j < 4; ++j)
        if (j != f && outside(glm::dvec3(kTetraNormals[f]) - glm::dvec3(kTetraNormals[j])))
          return true;
      return false;
    default: return false;
  }
}

// A block whose bounds' image covers more texels than this is looked at pixel by pixel: such a
// box holds a depth discontinuity (a near and a far surface), whose pixels' footprints cover a
// small part of the hull between them. Measured on the default scene at res 1024 (cube):
// without the limit the hulls cover 52 % of the rendered texels' tiles against 39 % for the
// pixels' own footprints; see docs/techniques/pipeline.md.
constexpr uint64_t kMaxHullTexels = 32 * kTexelTile * kTexelTile;

// A group of 2 × 2 blocks is decided by the box around it when its hulls cover at most this
// many texels (a few tiles' worth): on the default scene at res 1024 the tiles then cover
// 41.6 % of the rendered cube texels against 41.5 % block by block, for 0.32–0.33 against 0.34 ms.
constexpr uint64_t kMaxGroupTexels = 4 * kTexelTile * kTexelTile;

// Texel bounds of a paraboloid face's lookups at the points of a sphere of directions' cap, into
// `rect` (clipped to the texels the face owns); false when the cap holds the face's projection
// pole (its image is unbounded). The face's map is the stereographic projection from the pole
// −forward, (u, v) = (d̂·right, d̂·up)/(1 + d̂·forward), which maps circles on the sphere to
// circles: the cap of directions within α of ĉ (polar angle θ from forward) becomes the disk
// whose diameter joins the images of the cap's two points in ĉ's meridian, at signed radii
// tan((θ ∓ α)/2) along ĉ's azimuth. A cap wholly past the equator (θ − α > 90°) holds no point
// the face owns: rect stays empty.
bool paraboloid_cap_rect(const FaceLayout& layout, int f, const glm::dvec3& c, double alpha,
                         TexelRect& rect) {
  const LightFace& lf = layout.faces[size_t(f)];
  const double cz = std::clamp(glm::dot(c, glm::dvec3(lf.forward)), -1.0, 1.0);
  const double cx = glm::dot(c, glm::dvec3(lf.right)), cy = glm::dot(c, glm::dvec3(lf.up));
  const double pi = 3.14159265358979323846;
  const double theta = std::acos(cz);
  if (theta - alpha > 0.5 * pi) return true;
  if (theta + alpha >= 0.999 * pi) return false;
  const double r1 = std::tan(0.5 * (theta - alpha)), r2 = std::tan(0.5 * (theta + alpha));
  const double len = std::sqrt(cx * cx + cy * cy);
  const double ax = len > 0.0 ? cx / len : 1.0, ay = len > 0.0 ? cy / len : 0.0;
  const double mid = 0.5 * (r1 + r2), radius = 0.5 * (r2 - r1);
  const double su = double(lf.width) / (double(lf.right_edge) - double(lf.left));
  const double sv = double(lf.height) / (double(lf.top) - double(lf.bottom));
  const double g = double(layout.guard);
  // Clipped to the owned disk's square with one texel to spare, as hull_rect does.
  const double s_lo = std::max(g - 1.0, (mid * ax - radius - double(lf.left)) * su);
  const double s_hi =
      std::min(double(lf.width) - g + 1.0, (mid * ax + radius - double(lf.left)) * su);
  const double t_lo = std::max(g - 1.0, (double(lf.top) - (mid * ay + radius)) * sv);
  const double t_hi =
      std::min(double(lf.height) - g + 1.0, (double(lf.top) - (mid * ay - radius)) * sv);
  if (!(s_lo <= s_hi && t_lo <= t_hi)) return true;
  // bilinear_taps reads floor(st − ½) and the next texel; one texel more each side for rounding.
  auto texel = [](double v, int n) { return int(std::clamp(std::floor(v - 0.5), -1.0, double(n))); };
  rect = {std::max(0, texel(s_lo, lf.width) - 1), std::min(lf.width - 1, texel(s_hi, lf.width) + 2),
          std::max(0, texel(t_lo, lf.height) - 1), std::min(lf.height - 1, texel(t_hi, lf.height) + 2)};
  return true;
}

// The texels of every pixel of a block, per face, through its bounds grown by `reach` metres (the
// normal offset); false when the block must be decided pixel by pixel. The dual-paraboloid
// layout bounds the box by its circumscribed sphere, whose directions from the light form a cap
// (paraboloid_cap_rect on each face). A box in one face's cone
// (box_single_face; the projector's single face) is that face's hull. A box across face
// boundaries is, on each face in front of all its corners, the hull clipped to the texels the
// face owns (its image without the guard band: a receiver's coordinates lie there, and the
// margin covers their rounding); it needs the pixels when a face whose cone the box may reach
// (box_outside_face) has corners on both sides of its plane (the box passes beside the light),
// and when the hulls cover more than kMaxHullTexels.
bool box_rects(const FaceLayout& layout, const vec3& light, const BlockBounds& box, float reach,
               TexelRect* rects) {
  const glm::dvec3 lo = glm::dvec3(box.lo) - double(reach), hi = glm::dvec3(box.hi) + double(reach);
  if (layout.kind == FaceLayoutKind::DualParaboloid) {
    const glm::dvec3 centre = 0.5 * (lo + hi) - glm::dvec3(light);
    const double radius = 0.5 * glm::length(hi - lo), dist = glm::length(centre);
    // The light inside (or almost at) the sphere: every direction.
    if (!(dist > 1.001 * radius + 1e-9 * dist) || !std::isfinite(dist)) return false;
    // 1e-9 rad more for the rounding of asin and of the per-pixel path.
    const double alpha = std::asin(radius / dist) + 1e-9;
    uint64_t area = 0;
    for (size_t f = 0; f < layout.faces.size(); ++f) {
      if (!paraboloid_cap_rect(layout, int(f), centre / dist, alpha, rects[f])) return false;
      area += rects[f].area();
    }
    return area <= kMaxHullTexels;
  }
  const double inf = std::numeric_limits<double>::infinity();
  const int single = layout.kind == FaceLayoutKind::Projector
                         ? 0
                         : box_single_face(layout, light, box.lo, box.hi, reach, 1);
  if (single >= 0)
    return hull_rect(layout, light, single, lo, hi, -inf, inf, -inf, inf, rects[single]) ==
               Side::Front &&
           rects[single].area() <= kMaxHullTexels;
  const double g = double(layout.guard);
  uint64_t area = 0;
  for (size_t f = 0; f < layout.faces.size(); ++f) {
    const LightFace& lf = layout.faces[f];
    if (hull_rect(layout, light, int(f), lo, hi, g, double(lf.width) - g, g, double(lf.height) - g,
                  rects[f]) == Side::Across &&
        !box_outside_face(layout, int(f), lo, hi, light))
      return false;
    area += rects[f].area();
  }
  return area <= kMaxHullTexels;
}

}  // namespace

std::vector<FaceTiles> texel_tiles_needed_by_pixels(const Scene& scene, const GBuffer& g,
                                                    const FaceLayout& layout, const MapParams& p,
                                                    const std::vector<bool>& faces) {
  std::vector<FaceTiles> tiles = empty_tiles(layout);
  const PixelMarker marker(scene, g, layout, p, tiles);
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) { marker.mark_each(b, e); });
  drop_unneeded(tiles, faces);
  return tiles;
}

std::vector<FaceTiles> texel_tiles_needed(const Scene& scene, const GBuffer& g,
                                          const FaceLayout& layout, const MapParams& p,
                                          const std::vector<bool>& faces) {
  if (!g.has_block_bounds()) return texel_tiles_needed_by_pixels(scene, g, layout, p, faces);
  SL_CHECK(layout.faces.size() <= size_t(kMaxFaces));
  std::vector<FaceTiles> tiles = empty_tiles(layout);
  const PixelMarker marker(scene, g, layout, p, tiles);
  const vec3 light = scene.light.position;
  const float plane_texel = face_texel_plane_size(layout.faces[0]);
  const int bx = g.blocks_x(), by = g.blocks_y(), B = kGBufferBlock;
  auto mark = [&](const TexelRect* rects) {
    for (size_t f = 0; f < layout.faces.size(); ++f)
      if (!rects[f].empty())
        mark_texels(tiles, int(f), rects[f].x0, rects[f].x1, rects[f].y0, rects[f].y1);
  };
  // One block: its hulls, else its pixels.
  auto block = [&](size_t r, int b) {
    const BlockBounds& box = g.block_bounds[r * size_t(bx) + size_t(b)];
    if (box.empty()) return;
    TexelRect rects[kMaxFaces];
    if (box_rects(layout, light, box, normal_offset_reach(p, plane_texel, box, light), rects)) {
      mark(rects);
      return;
    }
    const int x0 = b * B, x1 = std::min(g.width, x0 + B);
    const int y0 = int(r) * B, y1 = std::min(g.height, y0 + B);
    // The block's rows lie a GBuffer row apart and are out of the caches by now (the render
    // ran since the lookups last read them): ask for all of them before the walk, which would
    // otherwise wait on each row's first lines in turn.
    for (int y = y0; y < y1; ++y) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x0), n = size_t(x1 - x0);
      prefetch_bytes(&g.position[i], n * sizeof(vec3));
      prefetch_bytes(&g.geo_normal[i], n * sizeof(vec3));
      prefetch_bytes(&g.covered[i], n);
    }
    for (int y = y0; y < y1; ++y) {
      const size_t i = size_t(y) * size_t(g.width);
      marker.mark_each(i + size_t(x0), i + size_t(x1));
    }
  };
  // 2 × 2 blocks at a time first: the box around the four is decided once when its hulls are
  // small (kMaxGroupTexels), which most are on smooth surfaces; they would mark about the same
  // tiles one by one. Else each block on its own.
  const int gx = (bx + 1) / 2, gy = (by + 1) / 2;
  parallel_for_chunks(size_t(gy), 1, [&](size_t q0, size_t q1) {
    for (size_t q = q0; q < q1; ++q)
      for (int c = 0; c < gx; ++c) {
        BlockBounds group;
        for (size_t r = 2 * q; r < std::min(size_t(by), 2 * q + 2); ++r)
          for (int b = 2 * c; b < std::min(bx, 2 * c + 2); ++b) {
            const BlockBounds& box = g.block_bounds[r * size_t(bx) + size_t(b)];
            if (box.empty()) continue;
            group.lo = glm::min(group.lo, box.lo);
            group.hi = glm::max(group.hi, box.hi);
          }
        if (group.empty()) continue;
        TexelRect rects[kMaxFaces];
        if (box_rects(layout, light, group, normal_offset_reach(p, plane_texel, group, light),
                      rects)) {
          uint64_t area = 0;
          for (size_t f = 0; f < layout.faces.size(); ++f) area += rects[f].area();
          if (area <= kMaxGroupTexels) {
            mark(rects);
            continue;
          }
        }
        for (size_t r = 2 * q; r < std::min(size_t(by), 2 * q + 2); ++r)
          for (int b = 2 * c; b < std::min(bx, 2 * c + 2); ++b) block(r, b);
      }
  });
  drop_unneeded(tiles, faces);
  return tiles;
}

}  // namespace shadowlab
