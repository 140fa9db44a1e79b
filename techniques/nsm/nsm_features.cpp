#include "techniques/nsm/nsm_features.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "techniques/lookup/map_receiver.h"

namespace shadowlab {

// Own namespace: the unity build compiles several files in one translation unit.
namespace nsm_features_impl {
namespace {

enum Feature { D, Z, ZF, CE, CC, NX, NY, NZ, ZMZF, ZOZF, CCOD, CER, kFeatureCount };

int feature_index(const std::string& name) {
  const std::vector<std::string>& all = nsm_feature_names();
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i] == name) return int(i);
  return -1;
}

// The pixel a receiver of the base map is made for: no bias of any kind, so its texel is the
// nearest one along p − L (the same face, coordinates and texel as csm's pcf=1 lookup).
Receiver nearest_receiver(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                          const vec3& pos, const vec3& n) {
  return make_receiver(layout, scene.light, p, 1.0f, 1.0f / scene.light.far, pos, n);
}

}  // namespace
}  // namespace nsm_features_impl

const std::vector<std::string>& nsm_feature_names() {
  static const std::vector<std::string> names = {"d",   "z",   "z_f",        "c_e",
                                                 "c_c", "n_x", "n_y",        "n_z",
                                                 "z_minus_zf", "z_over_zf", "cc_over_d", "c_e_r"};
  return names;
}

const std::vector<std::string>& nsm_network_features() {
  static const std::vector<std::string> names = {"z_over_zf", "z_minus_zf", "c_e_r", "d"};
  return names;
}

bool is_nsm_feature(const std::string& name) { return nsm_features_impl::feature_index(name) >= 0; }

float nsm_scene_scale(const Scene& scene) {
  return glm::length(scene.light.position - scene.camera.target) / kNsmScaleRef;
}

float nsm_size_code(float radius) { return 4.0f * radius / kNsmRadiusMax; }

MapParams nsm_base_map_params(int res, FaceLayoutKind layout) {
  MapParams p = default_map_params(layout, MapFilter::Depth);
  p.res = res;
  p.depth = DepthFormat::F32;
  p.bias = 0.0f;
  p.slope = 0.0f;
  p.normal = 0.0f;
  p.pcf = 1;
  p.rpdb = false;
  return p;
}

void build_nsm_base_map(const Scene& scene, const GBuffer& g, int res, LightMap& map) {
  const MapParams p = nsm_base_map_params(res);
  map.layout = map_layout(p, scene);
  render_light_map(scene, p, nsm_faces_needed(scene, g, map.layout), map);
}

std::vector<bool> nsm_faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout) {
  std::vector<bool> needed(layout.faces.size(), false);
  for (size_t i = 0; i < g.pixel_count(); ++i)
    if (g.covered[i]) needed[size_t(face_of(layout, g.position[i] - scene.light.position))] = true;
  return needed;
}

ImageU32 nsm_map_texels(const Scene& scene, const GBuffer& g, int res, const LightMap& map) {
  const MapParams p = nsm_base_map_params(res);
  ImageU32 t(g.width, g.height, 1, kNoTexel);
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      if (g.covered[i] && faces_light(g, i, scene.light.position))
        t.data[i] = nsm_features_impl::nearest_receiver(scene, map.layout, p, g.position[i],
                                                        g.geo_normal[i]).texel;
  });
  return t;
}

std::vector<float> nsm_map_distances(const Scene& scene, const GBuffer& g, int res,
                                     const LightMap& map) {
  const MapParams p = nsm_base_map_params(res);
  std::vector<float> z(g.pixel_count(), 0.0f);
  const float far = scene.light.far;
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i]) continue;
      const Receiver r = nsm_features_impl::nearest_receiver(scene, map.layout, p, g.position[i], g.geo_normal[i]);
      const size_t per_face = map.layout.faces[size_t(r.face)].texel_count();
      SL_CHECK(map.dist.rendered[size_t(r.face)]);
      const float stored = map.dist.distance[size_t(r.face)][r.texel - size_t(r.face) * per_face];
      z[i] = std::isinf(stored) ? far : stored * far;
    }
  });
  return z;
}

const std::vector<float>& NsmFeatures::plane(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return planes[i];
  SL_CHECK(false);
  return planes.front();
}

NsmFeatures compute_nsm_features(const Scene& scene, const GBuffer& g, int res,
                                 const LightMap& map, float scale, float size_code,
                                 const std::vector<std::string>& names) {
  using namespace nsm_features_impl;
  SL_CHECK(scale > 0.0f);
  std::vector<int> which;
  for (const std::string& n : names) {
    which.push_back(feature_index(n));
    SL_CHECK(which.back() >= 0);
  }
  NsmFeatures f;
  f.width = g.width;
  f.height = g.height;
  f.scale = scale;
  f.names = names;
  f.planes.assign(names.size(), std::vector<float>(g.pixel_count(), 0.0f));
  f.coverage.assign(g.pixel_count(), 0);
  const std::vector<float> z_map = nsm_map_distances(scene, g, res, map);
  const vec3 L = scene.light.position, eye = scene.camera.eye;
  const glm::mat3 view(camera_view(scene.camera));
  const float inv_s = 1.0f / scale;
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    float v[kFeatureCount];
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i]) continue;
      f.coverage[i] = 1;
      const vec3 pos = g.position[i], n = g.geo_normal[i];
      const vec3 to_l = L - pos, to_eye = eye - pos;
      const float zf_m = glm::length(to_l);
      const vec3 nv = view * n;
      v[D] = g.depth[i] * inv_s;
      v[Z] = z_map[i] * inv_s;
      v[ZF] = zf_m * inv_s;
      v[CE] = glm::dot(n, to_l) / zf_m;
      v[CC] = glm::dot(n, to_eye) / glm::length(to_eye);
      v[NX] = nv.x;
      v[NY] = nv.y;
      v[NZ] = nv.z;
      v[ZMZF] = v[Z] - v[ZF];
      v[ZOZF] = v[Z] / v[ZF];
      v[CCOD] = v[CC] / v[D];
      v[CER] = v[CE] + size_code;
      for (size_t k = 0; k < which.size(); ++k) f.planes[k][i] = v[which[k]];
    }
  });
  return f;
}

}  // namespace shadowlab
