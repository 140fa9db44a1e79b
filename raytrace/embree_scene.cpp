#include "raytrace/embree_scene.h"

#include <embree3/rtcore.h>

#include <cstring>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/texture.h"

namespace shadowlab {
// Named, not anonymous: EmbreeScene::Impl (external linkage) holds ErrorState and AlphaGeometry
// members, which GCC flags (-Wsubobject-linkage) outside the main file, as in a unity build.
namespace embree_scene_detail {

// First error reported by the device callback. Embree calls the callback from whichever thread
// hit the error and the callback cannot throw through C code, so the error is recorded here and
// thrown by throw_if_error once the Embree call has returned.
struct ErrorState {
  std::mutex mutex;
  RTCError code = RTC_ERROR_NONE;
  std::string message;
};

void on_device_error(void* user, RTCError code, const char* str) {
  if (code == RTC_ERROR_NONE) return;
  auto* state = static_cast<ErrorState*>(user);
  std::lock_guard<std::mutex> lock(state->mutex);
  if (state->code != RTC_ERROR_NONE) return;  // keep the first one: later ones are fallout
  state->code = code;
  state->message = str ? str : "(no message)";
}

// What an alpha filter needs about its mesh; owned by the Impl, pointed to by Embree.
struct AlphaGeometry {
  const ImageF* texture = nullptr;
  float cutoff = 0.5f;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<vec2> uvs;          // per vertex, or empty (uv = 0, as in the GBuffer)
};

// Intersection and occlusion filter of alpha-tested meshes: rejects every candidate hit whose
// alpha at the interpolated uv is below the cutoff.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const AlphaGeometry*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    vec2 uv(0.0f);
    if (!g->uvs.empty()) {
      const unsigned prim = RTCHitN_primID(args->hit, n, i);
      // Embree's barycentrics: p = (1 - u - v) p0 + u p1 + v p2.
      const float u = RTCHitN_u(args->hit, n, i);
      const float v = RTCHitN_v(args->hit, n, i);
      uv = barycentric_uv(g->uvs.data(), &g->indices[size_t(prim) * 3], u, v);
    }
    // The one alpha lookup and test of core, shared with the rasterizer.
    if (!alpha_test_passes(sample_alpha(*g->texture, uv), g->cutoff)) args->valid[i] = 0;
  }
}

}  // namespace embree_scene_detail

struct EmbreeScene::Impl {
  // Declared first: must outlive the device that points to it.
  embree_scene_detail::ErrorState errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  float scale = 0.0f;
  size_t meshes = 0;
  std::vector<ImageF> textures;  // copies of the referenced alpha textures (index = scene's)
  // Stable addresses for Embree.
  std::vector<std::unique_ptr<embree_scene_detail::AlphaGeometry>> alpha;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void throw_if_error(const char* what) {
    std::lock_guard<std::mutex> lock(errors.mutex);
    if (errors.code == RTC_ERROR_NONE) return;
    const int code = int(errors.code);
    const std::string message = std::string(what) + ": " + errors.message;
    errors.code = RTC_ERROR_NONE;
    errors.message.clear();
    throw EmbreeError(code, message);
  }
};

EmbreeScene::EmbreeScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  validate_scene(scene, "scene '" + scene.name + "'");
  Impl& im = *impl_;

  im.device = rtcNewDevice(nullptr);
  if (!im.device)
    throw EmbreeError(int(rtcGetDeviceError(nullptr)), "could not create an Embree device");
  // Registered right after creation so no later error goes unnoticed.
  rtcSetDeviceErrorFunction(im.device, embree_scene_detail::on_device_error, &im.errors);

  im.scene = rtcNewScene(im.device);
  im.throw_if_error("creating the scene");
  // Robust traversal: the reference must not lose hits to fast-but-inexact arithmetic.
  rtcSetSceneFlags(im.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);

  im.meshes = scene.meshes.size();
  const Bounds b = scene_bounds(scene);
  im.scale = b.valid() ? glm::length(b.extent()) : 0.0f;

  bool needs_filters = false;
  for (const Mesh& m : scene.meshes)
    if (m.triangle_count() > 0 && scene.materials[size_t(m.material)].alpha_texture >= 0)
      needs_filters = true;
  if (needs_filters && !rtcGetDeviceProperty(im.device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
    throw EmbreeError(int(RTC_ERROR_UNKNOWN),
                      "this Embree build has no filter functions; alpha-tested geometry needs them");

  // core's sample_alpha reads RGBA images only; anything else is bad input, reported here
  // rather than as an abort inside an Embree callback.
  for (const Material& mat : scene.materials) {
    if (mat.alpha_texture < 0) continue;
    const ImageF& tex = scene.textures[size_t(mat.alpha_texture)];
    if (tex.channels != 4 || tex.empty() || tex.data.size() != tex.pixel_count() * 4)
      throw InputError("scene '" + scene.name + "'",
                       "alpha texture " + std::to_string(mat.alpha_texture) + " of material '" +
                           mat.name + "' must be a non-empty RGBA image");
  }

  im.textures.resize(scene.textures.size());
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& mesh = scene.meshes[mi];
    const size_t tris = mesh.triangle_count();
    if (tris == 0) continue;  // no geometry: geomID mi stays unused

    RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    im.throw_if_error("creating a triangle geometry");
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                           mesh.positions.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                              RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), tris));
    if (vb && ib) {
      for (size_t v = 0; v < mesh.positions.size(); ++v) {
        vb[3 * v + 0] = mesh.positions[v].x;
        vb[3 * v + 1] = mesh.positions[v].y;
        vb[3 * v + 2] = mesh.positions[v].z;
      }
      std::memcpy(ib, mesh.indices.data(), tris * 3 * sizeof(unsigned));
    }

    const Material& mat = scene.materials[size_t(mesh.material)];
    if (mat.alpha_texture >= 0) {
      const size_t t = size_t(mat.alpha_texture);
      if (im.textures[t].empty()) im.textures[t] = scene.textures[t];
      auto g = std::make_unique<embree_scene_detail::AlphaGeometry>();
      g->texture = &im.textures[t];
      g->cutoff = mat.alpha_cutoff;
      g->indices = mesh.indices;
      g->uvs = mesh.uvs;
      rtcSetGeometryUserData(geom, g.get());
      rtcSetGeometryIntersectFilterFunction(geom, embree_scene_detail::alpha_filter);
      rtcSetGeometryOccludedFilterFunction(geom, embree_scene_detail::alpha_filter);
      im.alpha.push_back(std::move(g));
    }

    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(im.scene, geom, unsigned(mi));
    rtcReleaseGeometry(geom);  // the scene holds its own reference
    im.throw_if_error("building the geometry of a mesh");
  }

  rtcCommitScene(im.scene);
  im.throw_if_error("committing the scene");
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

float EmbreeScene::scene_scale() const {
  SL_CHECK(impl_);
  return impl_->scale;
}

size_t EmbreeScene::mesh_count() const {
  SL_CHECK(impl_);
  return impl_->meshes;
}

size_t EmbreeScene::alpha_mesh_count() const {
  SL_CHECK(impl_);
  return impl_->alpha.size();
}

void* EmbreeScene::native_scene() const {
  SL_CHECK(impl_);
  return impl_->scene;
}

void EmbreeScene::throw_if_error(const char* what) const {
  SL_CHECK(impl_);
  impl_->throw_if_error(what);
}

}  // namespace shadowlab
