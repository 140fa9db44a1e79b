#include "lab/nsm_dataset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/hash.h"
#include "core/light_fit.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "lab/provenance.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"
#include "scenes/scene_registry.h"
#include "techniques/nsm/nsm_features.h"

namespace shadowlab {

namespace nsm_dataset_impl {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The frame's uniform numbers: copy 0..3, dimension k.
float uniform(const NsmDatasetParams& p, int frame, int copy, uint64_t k) {
  return rng_float(rng_hash(uint64_t(frame), uint64_t(copy), p.seed, k));
}

// Dimensions of the frame's hashes (copy 0 unless said).
enum Dim : uint64_t { kOrbit = 0, kDolly, kLightTurn, kLightReach, kCropX, kCropY, kSplit,
                      kBallZ = 10, kBallPhi, kBallR, kPixelR, kPixelPhi, kReference = 100 };

vec3 turn_about_y(vec3 v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return vec3(float(c * v.x + s * v.z), v.y, float(-s * v.x + c * v.z));
}

double max_radius(const NsmDatasetParams& p) {
  double r = 0.0;
  for (double v : p.radii) r = std::max(r, v);
  return r;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xFF));
}
void pad64(std::string& out) { out.append((64 - out.size() % 64) % 64, '\0'); }
template <class T>
void put_plane(std::string& out, const std::vector<T>& v) {
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  pad64(out);
}

void check_split(const NsmSplit& s, const std::vector<std::string>& scenes, const char* flag) {
  for (const std::string& n : s.scenes)
    if (!contains(scenes, n)) throw InputError(flag, "scene '" + n + "' is not among --scenes");
  if (s.fraction < 0.0 || s.fraction > 1.0)
    throw InputError(flag, "a fraction must lie in [0, 1]");
}

}  // namespace
}  // namespace nsm_dataset_impl

void check_nsm_dataset_params(NsmDatasetParams& p) {
  using namespace nsm_dataset_impl;
  if (p.crop_w > p.width || p.crop_h > p.height)
    throw InputError("--crop", std::to_string(p.crop_w) + "x" + std::to_string(p.crop_h) +
                                   " is larger than the frame (" + std::to_string(p.width) + "x" +
                                   std::to_string(p.height) + ")");
  const std::vector<std::string> known = builtin_scene_names();
  for (size_t i = 0; i < p.scenes.size(); ++i) {
    if (!contains(known, p.scenes[i])) make_builtin_scene(p.scenes[i]);  // its InputError
    for (size_t j = 0; j < i; ++j)
      if (p.scenes[j] == p.scenes[i]) throw InputError("--scenes", "'" + p.scenes[i] + "' given twice");
  }
  check_split(p.val, p.scenes, "--split-val");
  check_split(p.test, p.scenes, "--split-test");
  for (const std::string& n : p.val.scenes)
    if (contains(p.test.scenes, n))
      throw InputError("--split-val", "scene '" + n + "' is also in --split-test");
  if (p.val.scenes.empty() && p.test.scenes.empty() && p.val.fraction + p.test.fraction > 1.0)
    throw InputError("--split-val", "the val and test fractions add up to more than 1");
  if (p.features.empty()) p.features = nsm_feature_names();
  for (size_t i = 0; i < p.features.size(); ++i) {
    if (!is_nsm_feature(p.features[i]))
      throw InputError("--features", "unknown feature '" + p.features[i] + "'");
    for (size_t j = 0; j < i; ++j)
      if (p.features[j] == p.features[i])
        throw InputError("--features", "'" + p.features[i] + "' given twice");
  }
}

Scene nsm_frame_scene(const Scene& base, const NsmDatasetParams& p, int frame) {
  using namespace nsm_dataset_impl;
  Scene s = base;
  s.projector.enabled = false;  // a sphere light at the projector's place
  s.camera.width = p.width;
  s.camera.height = p.height;
  const vec3 t = s.camera.target;
  const double orbit = (-40.0 + 80.0 * uniform(p, frame, 0, kOrbit)) * kPi / 180.0;
  const float dolly = 0.85f + 0.3f * uniform(p, frame, 0, kDolly);
  s.camera.eye = t + turn_about_y(s.camera.eye - t, orbit) * dolly;
  const double turn = (-30.0 + 60.0 * uniform(p, frame, 0, kLightTurn)) * kPi / 180.0;
  const float reach = 0.9f + 0.2f * uniform(p, frame, 0, kLightReach);
  s.light.position = t + turn_about_y(base.light.position - t, turn) * reach;
  s.light.radius = float(max_radius(p));
  if (light_fit_problem(s).kind != LightFitProblem::None) s.light.position = base.light.position;
  s.light.radius = 0.0f;
  cover_scene_with_light_range(s);
  return s;
}

Scene nsm_perturbed_scene(const Scene& frame, const NsmDatasetParams& p, int frame_index, int copy) {
  using namespace nsm_dataset_impl;
  Scene s = frame;
  auto u = [&](uint64_t k) { return double(uniform(p, frame_index, copy, k)); };
  const vec3 L = s.light.position, t = s.camera.target, eye = s.camera.eye;
  // The light: uniform in the ball (uniform direction, radius ∝ cbrt of a uniform).
  const double ball = std::max(2.0 * double(glm::length(L - t)) / p.base_res, 0.1 * max_radius(p));
  const double z = 1.0 - 2.0 * u(kBallZ), phi = 2.0 * kPi * u(kBallPhi);
  const double rxy = std::sqrt(std::max(0.0, 1.0 - z * z)), r = ball * std::cbrt(u(kBallR));
  s.light.position = L + vec3(float(r * rxy * std::cos(phi)), float(r * rxy * std::sin(phi)),
                              float(r * z));
  // The camera: uniform in the disk of 0.5 px at the target's depth, in the image plane.
  const double pixel = 2.0 * std::tan(double(s.camera.fov_y_deg) * kPi / 360.0) *
                       double(glm::length(t - eye)) / p.height;
  const double rho = 0.5 * pixel * std::sqrt(u(kPixelR)), psi = 2.0 * kPi * u(kPixelPhi);
  const vec3 f = glm::normalize(t - eye);
  const vec3 right = glm::normalize(glm::cross(f, s.camera.up)), up = glm::cross(right, f);
  const vec3 delta = float(rho * std::cos(psi)) * right + float(rho * std::sin(psi)) * up;
  s.camera.eye = eye + delta;
  s.camera.target = t + delta;
  cover_scene_with_light_range(s);
  return s;
}

std::array<int, 4> nsm_frame_crop(const NsmDatasetParams& p, int frame) {
  using namespace nsm_dataset_impl;
  const int nx = p.width - p.crop_w + 1, ny = p.height - p.crop_h + 1;
  const int x0 = std::min(int(uniform(p, frame, 0, kCropX) * float(nx)), nx - 1);
  const int y0 = std::min(int(uniform(p, frame, 0, kCropY) * float(ny)), ny - 1);
  return {x0, y0, p.crop_w, p.crop_h};
}

GBuffer crop_gbuffer(const GBuffer& g, const std::array<int, 4>& c) {
  GBuffer o;
  o.resize(c[2], c[3]);
  for (int y = 0; y < c[3]; ++y)
    for (int x = 0; x < c[2]; ++x) {
      const size_t i = size_t(y) * size_t(c[2]) + size_t(x);
      const size_t j = size_t(y + c[1]) * size_t(g.width) + size_t(x + c[0]);
      o.position[i] = g.position[j];
      o.geo_normal[i] = g.geo_normal[j];
      o.depth[i] = g.depth[j];
      o.mesh_id[i] = g.mesh_id[j];
      o.prim_id[i] = g.prim_id[j];
      o.covered[i] = g.covered[j];
    }
  o.normal.clear();
  o.uv.clear();
  return o;
}

uint64_t nsm_file_hash(const std::string& bytes) {
  SL_CHECK(bytes.size() >= 8);
  uint64_t h = 0;
  std::memcpy(&h, bytes.data() + bytes.size() - 8, 8);
  return h;
}

std::string nsm_frame_split(const NsmDatasetParams& p, int frame) {
  using namespace nsm_dataset_impl;
  const std::string& scene = p.scenes[size_t(frame) % p.scenes.size()];
  const double u = uniform(p, frame, 0, kSplit);
  if (!p.test.scenes.empty()) {
    if (contains(p.test.scenes, scene)) return "test";
  } else if (u < p.test.fraction) {
    return "test";
  }
  if (!p.val.scenes.empty()) {
    if (contains(p.val.scenes, scene)) return "val";
  } else if (u >= 1.0 - p.val.fraction) {
    return "val";
  }
  return "train";
}

namespace nsm_dataset_impl {
namespace {

std::string frame_file(const NsmDatasetParams& p, const Scene& base, const EmbreeScene& rt,
                       int frame) {
  const Scene s0 = nsm_frame_scene(base, p, frame);
  const std::array<int, 4> crop = nsm_frame_crop(p, frame);
  const float scale = nsm_scene_scale(s0);
  std::string planes;
  GBuffer crop0;
  for (int c = 0; c < 4; ++c) {
    const Scene sc = c == 0 ? s0 : nsm_perturbed_scene(s0, p, frame, c);
    GBuffer g = crop_gbuffer(render_gbuffer(sc), crop);
    LightMap map;
    build_nsm_base_map(sc, g, p.base_res, map);
    // c_e_r is stored with r_e = 0: the reader adds the code of the radius it draws.
    const NsmFeatures f = compute_nsm_features(sc, g, p.base_res, map, scale, 0.0f, p.features);
    for (const std::vector<float>& plane : f.planes) put_plane(planes, plane);
    put_plane(planes, f.coverage);
    if (c == 0) crop0 = std::move(g);
  }
  for (size_t k = 0; k < p.radii.size(); ++k) {
    Scene sr = s0;
    sr.light.radius = float(p.radii[k]);
    const uint64_t seed = rng_hash(uint64_t(frame), 0, p.seed, kReference + k);
    put_plane(planes, soft_visibility(rt, sr, crop0, p.spp, seed).data);
  }
  nlohmann::ordered_json h;
  h["width"] = p.crop_w;
  h["height"] = p.crop_h;
  h["features"] = p.features;
  h["copies"] = 4;
  h["radii"] = p.radii;
  h["spp"] = p.spp;
  h["scene"] = base.name;
  h["frame"] = frame;
  h["seed"] = p.seed;
  h["crop"] = crop;
  h["scale"] = scale;
  h["frame_size"] = {p.width, p.height};
  h["base_res"] = p.base_res;
  h["r_max"] = kNsmRadiusMax;
  h["scale_ref"] = kNsmScaleRef;
  const std::string header = h.dump();
  std::string out = "NSMF";
  put_u32(out, 1);
  put_u32(out, uint32_t(header.size()));
  out += header;
  pad64(out);
  out += planes;
  Fnv1a hash;
  hash.bytes(out.data(), out.size());
  const uint64_t v = hash.h;
  out.append(reinterpret_cast<const char*>(&v), 8);
  return out;
}

}  // namespace
}  // namespace nsm_dataset_impl

std::string nsm_frame_file(const NsmDatasetParams& p, const Scene& base, int frame) {
  Scene geometry = base;
  geometry.projector.enabled = false;
  geometry.light.radius = 0.0f;
  const EmbreeScene rt(geometry);
  return nsm_dataset_impl::frame_file(p, base, rt, frame);
}

uint64_t write_nsm_dataset(const NsmDatasetParams& p, const std::string& dir,
                           const std::vector<std::string>& command, bool progress) {
  using namespace nsm_dataset_impl;
  std::map<std::string, Scene> scenes;
  std::map<std::string, std::unique_ptr<EmbreeScene>> rts;
  for (const std::string& n : p.scenes) {
    scenes[n] = make_builtin_scene(n);
    Scene geometry = scenes[n];
    geometry.projector.enabled = false;
    geometry.light.radius = 0.0f;
    rts[n] = std::make_unique<EmbreeScene>(geometry);
  }
  nlohmann::ordered_json splits = {{"train", nlohmann::json::array()},
                                   {"val", nlohmann::json::array()},
                                   {"test", nlohmann::json::array()}};
  std::map<std::string, std::vector<std::string>> split_scenes;
  Fnv1a all;
  std::filesystem::create_directories(dir + "/frames");
  for (int i = 0; i < p.frames; ++i) {
    const std::string& name = p.scenes[size_t(i) % p.scenes.size()];
    const std::string bytes = frame_file(p, scenes[name], *rts[name], i);
    char file[32];
    std::snprintf(file, sizeof file, "%06d.nsmf", i);
    write_text_file(dir + "/frames/" + file, bytes);
    all.u64(nsm_file_hash(bytes));
    const std::string split = nsm_frame_split(p, i);
    splits[split].push_back(file);
    if (!contains(split_scenes[split], name)) split_scenes[split].push_back(name);
    if (progress) std::fprintf(stderr, "\rnsm_data: frame %d/%d", i + 1, p.frames);
  }
  if (progress) std::fprintf(stderr, "\n");
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(all.h));
  nlohmann::ordered_json m;
  m["format"] = "nsmf";
  m["version"] = 1;
  m["command"] = command;
  m["commit"] = build_commit();
  m["hash"] = hex;
  m["frames"] = p.frames;
  m["features"] = p.features;
  m["radii"] = p.radii;
  m["splits"] = splits;
  nlohmann::ordered_json ss;
  for (const char* k : {"train", "val", "test"}) ss[k] = split_scenes[k];
  m["split_scenes"] = ss;
  write_text_file(dir + "/manifest.json", m.dump(2) + "\n");
  return all.h;
}

}  // namespace shadowlab
