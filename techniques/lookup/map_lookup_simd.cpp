#include "techniques/lookup/map_lookup_simd.h"

#include <algorithm>
#include <climits>
#include <cstring>

#include "core/error.h"
#include "core/projector.h"

#if defined(__x86_64__)
#include "techniques/lookup/map_lookup_avx2.h"
#endif

namespace shadowlab {

namespace {

template <class Planes>
PlaneGather gather_planes(const Planes& planes) {
  PlaneGather g;
  uintptr_t lowest = UINTPTR_MAX;
  for (const auto& d : planes)
    if (!d.empty()) lowest = std::min(lowest, reinterpret_cast<uintptr_t>(d.data()));
  if (lowest == UINTPTR_MAX || planes.size() > 8) return g;
  g.ok = true;
  g.base = reinterpret_cast<const float*>(lowest);
  for (size_t i = 0; i < planes.size(); ++i) {
    if (planes[i].empty()) continue;
    const uintptr_t bytes = reinterpret_cast<uintptr_t>(planes[i].data()) - lowest;
    const uintptr_t floats = bytes / sizeof(float);
    if (bytes % sizeof(float) != 0 || floats + planes[i].size() > uintptr_t(INT32_MAX))
      g.ok = false;
    else
      g.offset[i] = int32_t(floats);
  }
  return g;
}

}  // namespace

PlaneGather plane_gather(const std::vector<std::vector<float>>& planes) {
  return gather_planes(planes);
}

PlaneGather plane_gather(const std::vector<LineAlignedFloats>& planes) {
  return gather_planes(planes);
}

MapLookupConsts map_lookup_consts(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                                  const std::vector<LineAlignedFloats>& face_depth) {
  SL_CHECK(layout.faces.size() <= 8);
  MapLookupConsts c;
  c.light = scene.light.position;
  c.inv_far = 1.0f / scene.light.far;
  c.bias = p.bias;
  c.slope_k = p.slope * map_reach(p);
  c.plane_texel = face_texel_plane_size(layout.faces[0]);
  c.kind = layout.kind;
  if (c.kind == FaceLayoutKind::Projector) {
    const ProjectorFrame fr = projector_frame(scene.projector);
    c.proj_forward = fr.forward;
    c.proj_right = fr.right;
    c.proj_up = fr.up;
    c.proj_tan_x = fr.tan_x;
    c.proj_tan_y = fr.tan_y;
  }
  // The rendered faces' storage, gathered from one base.
  const PlaneGather pg = plane_gather(face_depth);
  c.gather_ok = pg.ok;
  c.depth_base = pg.base;
  for (int i = 0; i < 8; ++i) c.offset[i] = pg.offset[i];
  for (size_t i = 0; i < layout.faces.size(); ++i) {
    const LightFace& f = layout.faces[i];
    for (int k = 0; k < 3; ++k) {
      c.fwd[k][i] = f.forward[k];
      c.right[k][i] = f.right[k];
      c.up[k][i] = f.up[k];
    }
    c.left[i] = f.left;
    c.range_u[i] = f.right_edge - f.left;
    c.top[i] = f.top;
    c.range_v[i] = f.top - f.bottom;
    c.width_f[i] = float(f.width);
    c.height_f[i] = float(f.height);
    c.width[i] = f.width;
    c.height[i] = f.height;
    c.base[i] = int32_t(i * f.texel_count());
  }
  return c;
}

namespace {

void merge8_scalar(const Receivers8& r, const float* vis, float* mask, uint32_t* texels) {
  for (int k = 0; k < 8; ++k) {
    mask[k] = r.active[k] ? std::clamp(vis[k], 0.0f, 1.0f) : r.mask[k];
    if (texels) texels[k] = uint32_t(r.texel[k]);
  }
}

constexpr LookupKernels kLookupScalar{Isa::scalar, nullptr, nullptr, nullptr, nullptr, nullptr,
                                nullptr, nullptr, nullptr, nullptr, nullptr, merge8_scalar};

#if defined(__x86_64__)
constexpr LookupKernels kLookupAvx2{Isa::avx2,
                              lookup_avx2::receivers8,
                              lookup_avx2::depth1,
                              lookup_avx2::pcf,
                              lookup_avx2::faces8,
                              lookup_avx2::footprint_tiles8,
                              lookup_avx2::bilinear8_pairs,
                              lookup_avx2::bilinear8_interleaved2,
                              lookup_avx2::bilinear8_interleaved4,
                              lookup_avx2::bilinear8_mix4,
                              lookup_avx2::prefetch8,
                              lookup_avx2::merge8};
#endif

}  // namespace

const LookupKernels& lookup_kernels(Isa isa) {
#if defined(__x86_64__)
  if (isa >= Isa::avx2) return kLookupAvx2;
#endif
  (void)isa;
  return kLookupScalar;
}

}  // namespace shadowlab
