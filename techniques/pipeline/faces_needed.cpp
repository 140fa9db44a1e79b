#include "techniques/pipeline/faces_needed.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {

namespace {

using dvec3 = glm::dvec3;

// Minimum of a·d over the box centre ± half (every d in it).
double box_min(const dvec3& a, const dvec3& centre, const dvec3& half) {
  return glm::dot(a, centre) - glm::dot(glm::abs(a), half);
}

// A box [lo, hi] grown by `reach`, relative to the light: centre ± half, with the margin `eps`
// that covers the per-pixel path's float rounding (positions, the offset point, p − L and the
// dot products stay far below 1e-5 of the coordinates' magnitude).
struct LightBox {
  dvec3 centre, half;
  double eps;
  bool finite;
  LightBox(const vec3& light, const vec3& lo, const vec3& hi, float reach) {
    const dvec3 dlo(lo), dhi(hi), L(light);
    centre = 0.5 * (dlo + dhi) - L;
    half = 0.5 * (dhi - dlo) + dvec3(double(reach));
    finite = std::isfinite(glm::dot(centre, centre)) && std::isfinite(glm::dot(half, half));
    const double scale = std::max({std::fabs(dlo.x), std::fabs(dlo.y), std::fabs(dlo.z),
                                   std::fabs(dhi.x), std::fabs(dhi.y), std::fabs(dhi.z)}) +
                         std::max({std::fabs(L.x), std::fabs(L.y), std::fabs(L.z)}) +
                         double(reach);
    eps = 1e-5 * scale;
  }
  // a·d > 0 for every d in the box, by the margin (false for NaN).
  bool above(const dvec3& a) const {
    const double a1 = std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
    return box_min(a, centre, half) > eps * a1;
  }
};

// Face f's cone of directions from the light as half-spaces a·d >= 0 (face_of gives f strictly
// inside them, and never f where one is strictly negative); the count of planes.
int face_cone(const FaceLayout& layout, int f, dvec3* planes) {
  const LightFace& face = layout.faces[size_t(f)];
  const dvec3 fwd(face.forward), right(face.right), up(face.up);
  switch (layout.kind) {
    case FaceLayoutKind::Cube:
      planes[0] = fwd + right;
      planes[1] = fwd - right;
      planes[2] = fwd + up;
      planes[3] = fwd - up;
      return 4;
    case FaceLayoutKind::Tetrahedron: {
      int n = 0;
      for (int j = 0; j < 4; ++j)
        if (j != f) planes[n++] = dvec3(kTetraNormals[f]) - dvec3(kTetraNormals[j]);
      return n;
    }
    case FaceLayoutKind::DualParaboloid:
      // The two faces look opposite ways (face 1's forward is −face 0's), and face_of gives 0
      // where d·forward0 >= 0: each face's half-space is its own forward.
      planes[0] = fwd;
      return 1;
    case FaceLayoutKind::Projector: return 0;
  }
  return 0;
}

}  // namespace

int box_single_face(const FaceLayout& layout, const vec3& light, const vec3& lo, const vec3& hi,
                    float reach, int cross_pcf) {
  if (layout.kind == FaceLayoutKind::Projector) return -1;
  const LightBox box(light, lo, hi, reach);
  if (!box.finite) return -1;
  auto holds = [&](const dvec3& a) { return box.above(a); };
  const vec3 c(box.centre);
  if (c == vec3(0.0f)) return -1;
  const int f = face_of(layout, c);
  const LightFace& face = layout.faces[size_t(f)];
  const dvec3 fwd(face.forward), right(face.right), up(face.up);
  dvec3 planes[4];
  const int n = face_cone(layout, f, planes);
  for (int k = 0; k < n; ++k)
    if (!holds(planes[k])) return -1;
  if (cross_pcf > 1) {
    if (face.paraboloid) return -1;
    // pcf_taps_inside holds for texel coordinates st in [half + 1.5, size − pcf + half − 0.5]
    // on both axes (one texel inside its exact limits); in plane coordinates u = d·right /
    // d·forward and v = d·up / d·forward these are half-spaces through the light.
    const int hk = (cross_pcf - 1) / 2;
    const double st_lo = hk + 1.5;
    const double sx_hi = face.width - cross_pcf + hk - 0.5, sy_hi = face.height - cross_pcf + hk - 0.5;
    if (!(st_lo < sx_hi && st_lo < sy_hi)) return -1;
    const double du = (double(face.right_edge) - face.left) / face.width;
    const double dv = (double(face.top) - face.bottom) / face.height;
    const double u_lo = face.left + st_lo * du, u_hi = face.left + sx_hi * du;
    const double v_hi = face.top - st_lo * dv, v_lo = face.top - sy_hi * dv;
    if (!(holds(right - u_lo * fwd) && holds(u_hi * fwd - right) && holds(up - v_lo * fwd) &&
          holds(v_hi * fwd - up)))
      return -1;
  }
  return f;
}

float pcf_tap_reach(const FaceLayout& layout, int pcf, const BlockBounds& box, const vec3& light,
                    float reach) {
  if (pcf <= 1) return 0.0f;
  // The taps lie within (pcf − 1)/2 + 1.5 texels of the lookup point on each axis of its face
  // (for_each_pcf_tap): directions of points within √2·((pcf − 1)/2 + 2) plane texels × the
  // point's forward distance, at most its distance from the light, of it.
  double plane_step = 0.0;
  for (const LightFace& lf : layout.faces)
    plane_step = std::max({plane_step, (double(lf.right_edge) - lf.left) / lf.width,
                           (double(lf.top) - lf.bottom) / lf.height});
  const vec3 far_corner = glm::max(glm::abs(box.lo - light), glm::abs(box.hi - light));
  return float(1.01 * std::sqrt(2.0) * ((pcf - 1) / 2 + 2) * plane_step *
               (double(glm::length(far_corner)) + reach));
}

bool box_misses_faces(const FaceLayout& layout, const vec3& light, const vec3& lo,
                      const vec3& hi, float reach, uint32_t faces) {
  if (layout.kind == FaceLayoutKind::Projector) return false;
  const LightBox box(light, lo, hi, reach);
  if (!box.finite) return false;
  for (size_t f = 0; f < layout.faces.size() && f < 32; ++f) {
    if (!((faces >> f) & 1u)) continue;
    // Outside the cone: some half-space's a·d < 0 over the whole box, i.e. (−a)·d > 0.
    dvec3 planes[4];
    const int n = face_cone(layout, int(f), planes);
    bool outside = false;
    for (int k = 0; k < n && !outside; ++k) outside = box.above(-planes[k]);
    if (!outside) return false;
  }
  return true;
}

namespace {

// The block path of faces_needed: a block whose bounds decide it (box_single_face) adds its
// face if any of its pixels is looked up, which is only walked for (up to its first looked-up
// row) when the face is not already known to be needed; every other block walks its pixels.
// `known`: faces already found (the sparse sample). The result is a union, so it does not depend
// on the order the blocks are visited in.
template <class Scan>
std::vector<bool> faces_needed_by_blocks(const GBuffer& g, const FaceLayout& layout,
                                         const MapParams& p, const vec3& light, uint32_t known,
                                         const Scan& scan) {
  const int bx = g.blocks_x(), by = g.blocks_y(), B = kGBufferBlock;
  const bool cross = p.filter == MapFilter::Depth && p.seams == SeamMode::Cross && p.pcf > 1;
  const float plane_texel = face_texel_plane_size(layout.faces[0]);
  const size_t nf = layout.faces.size();
  const uint32_t all = nf >= 32 ? ~0u : (1u << nf) - 1u;
  // Faces found so far by any thread: a block whose face is among them needs no walk, and once
  // every face is found the remaining blocks are skipped. Every block ORs what it found in, so
  // at the end this is the answer, the union, whichever thread found a face first.
  std::atomic<uint32_t> found{known};
  parallel_for_chunks(size_t(by), 1, [&](size_t r0, size_t r1) {
    uint32_t f = known;
    for (size_t r = r0; r < r1; ++r) {
      size_t unused = 0;
      f |= found.load(std::memory_order_relaxed);
      for (int b = 0; b < bx && f != all; ++b) {
        const BlockBounds& box = g.block_bounds[r * size_t(bx) + size_t(b)];
        if (box.empty()) continue;
        const float reach = normal_offset_reach(p, plane_texel, box, light);
        const int face = box_single_face(layout, light, box.lo, box.hi, reach, cross ? p.pcf : 1);
        if (face >= 0 && ((f >> face) & 1u)) continue;
        // A block across faces that are all known already (its box, and with cross seams its
        // taps' reach, outside every other face's cone) needs no walk either: it can add no face.
        if (face < 0) {
          const float grown = reach + (cross ? pcf_tap_reach(layout, p.pcf, box, light, reach) : 0.0f);
          if (box_misses_faces(layout, light, box.lo, box.hi, grown, all & ~f)) continue;
        }
        const int x0 = b * B, x1 = std::min(g.width, x0 + B);
        const int y0 = int(r) * B, y1 = std::min(g.height, y0 + B);
        for (int y = y0; y < y1; ++y) {
          const size_t i = size_t(y) * size_t(g.width);
          scan(i + size_t(x0), i + size_t(x1), f, unused);
          if ((face >= 0 && ((f >> face) & 1u)) || f == all) break;
        }
        f |= found.fetch_or(f, std::memory_order_relaxed);
      }
    }
  });
  const uint32_t f = found.load();
  std::vector<bool> needed(nf, false);
  for (size_t i = 0; i < nf; ++i) needed[i] = (f >> i) & 1u;
  return needed;
}

}  // namespace

std::vector<bool> faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                               const MapParams& p, size_t* looked_up) {
  const size_t grain = 8192;
  const size_t chunks = (g.pixel_count() + grain - 1) / grain;
  const size_t nf = layout.faces.size();
  const bool projector = layout.kind == FaceLayoutKind::Projector;
  const ProjectorFrame frame = projector ? projector_frame(scene.projector) : ProjectorFrame{};
  // Only cross-face PCF taps can reach another face; with a guard band every tap stays in the
  // receiver's own face image.
  const bool cross = p.filter == MapFilter::Depth && p.seams == SeamMode::Cross && p.pcf > 1;
  // PCSS kernels grow with the penumbra and may reach any face: once one pixel is looked up,
  // every face is needed.
  const bool pcss = p.filter == MapFilter::Pcss;
  const uint32_t all = nf >= 32 ? ~0u : (1u << nf) - 1u;
  // The AVX2 kernel (no normal offset) takes groups of 8 pixels; the scalar loop is its oracle
  // and takes the rest.
  const Faces8Fn faces8 = p.normal <= 0.0f ? lookup_kernels(process_isa()).faces8 : nullptr;
  const MapLookupConsts consts =
      faces8 ? map_lookup_consts(scene, layout, p, {}) : MapLookupConsts{};
  // Faces (bit f: face f) and looked-up pixels of the pixels [b, e).
  auto scan = [&](size_t b, size_t e, uint32_t& f, size_t& count) {
    auto walk_taps = [&](int face, vec2 st) {
      for_each_pcf_tap(layout, face, st, p.pcf, [&](int ff, int, int, float) { f |= 1u << ff; });
    };
    size_t i = b;
    if (faces8)
      for (; i + 8 <= e; i += 8) {
        Receivers8 rest;
        const Faces8 r = faces8(consts, cross ? p.pcf : 1, &g.position[i].x, &g.geo_normal[i].x,
                                &g.covered[i], rest);
        f |= r.bits;
        if (pcss && r.looked_up) f |= all;
        count += r.looked_up;
        if (r.rest)
          for (int k = 0; k < 8; ++k)
            if (rest.active[k]) walk_taps(rest.face[k], vec2(rest.sx[k], rest.sy[k]));
      }
    for (; i < e; ++i) {
      if (!g.covered[i] || !faces_light(g, i, scene.light.position)) continue;
      vec2 st;
      if (projector && !projector_slide_coords(frame, scene.light.position, g.position[i], st))
        continue;
      ++count;
      if (pcss) f |= all;
      const vec3 to_p =
          lookup_point(layout, scene.light, p, g.position[i], g.geo_normal[i]) - scene.light.position;
      const int face = face_of(layout, to_p);
      f |= 1u << face;
      if (!cross) continue;
      // Interior pixels (the whole footprint inside the face) need nothing more: the per-tap
      // walk runs only within the filter's reach of a face edge.
      const LightFace& lf = layout.faces[size_t(face)];
      const vec2 c = face_texel_coords(lf, to_p);
      if (!pcf_taps_inside(c, p.pcf, lf.width, lf.height)) walk_taps(face, c);
    }
  };
  if (!looked_up) {
    // A sparse sample first (8 pixels of every 512): when it already needs every face, so does
    // the whole image, and the pass ends after 1/64 of the work. Otherwise the blocks decide
    // (with block bounds), else every pixel is walked below. Every way the answer is the exact
    // set of faces (docs/techniques/pipeline.md: stage 2).
    uint32_t f = 0;
    size_t unused = 0;
    for (size_t b = 0; b < g.pixel_count() && f != all; b += 512)
      scan(b, std::min(b + 8, g.pixel_count()), f, unused);
    if (f == all) return std::vector<bool>(nf, true);
    if (g.has_block_bounds() && !pcss && !projector)
      return faces_needed_by_blocks(g, layout, p, scene.light.position, f, scan);
  }
  std::vector<uint32_t> flags(chunks, 0);  // bit f: face f needed
  std::vector<size_t> counts(chunks, 0);
  parallel_for_chunks(g.pixel_count(), grain, [&](size_t b, size_t e) {
    uint32_t f = 0;
    size_t count = 0;
    scan(b, e, f, count);
    flags[b / grain] = f;
    counts[b / grain] = count;
  });
  std::vector<bool> needed(nf, false);
  for (const uint32_t f : flags)
    for (size_t i = 0; i < nf; ++i) needed[i] = needed[i] || ((f >> i) & 1u);
  if (looked_up) {
    *looked_up = 0;
    for (size_t c : counts) *looked_up += c;
  }
  return needed;
}

}  // namespace shadowlab
