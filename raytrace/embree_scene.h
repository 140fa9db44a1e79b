#pragma once
// EmbreeScene: RAII owner of an Embree device and a committed Embree scene built from a
// shadowlab::Scene. Embree itself stays inside raytrace/*.cpp: this header hands out the scene
// only as an opaque pointer.
//
// Layout: one triangle geometry per non-empty Mesh with geomID == mesh index (hits map back to
// Scene::meshes[geomID], primID == triangle index in that mesh). Meshes whose material has an
// alpha texture get intersection and occlusion filter functions that reject a hit unless
// alpha_test_passes(sample_alpha(texture, uv at the hit), alpha_cutoff) — core/texture.h, the
// same lookup and test as the rasterizer's; uv at the hit = (1 − u − v)·uv0 + u·uv1 + v·uv2 with
// Embree's barycentrics, or 0 for a mesh without uvs. Opaque materials get no filter and never
// touch a texture. No back-face culling.
#include <memory>
#include <stdexcept>
#include <string>

#include "core/scene.h"

namespace shadowlab {

// An error reported by Embree (through the device error callback) or by device creation.
struct EmbreeError : std::runtime_error {
  EmbreeError(int code, const std::string& message)
      : std::runtime_error("Embree error " + std::to_string(code) + ": " + message), code(code) {}
  int code;  // RTCError value
};

class EmbreeScene {
 public:
  // Validates `scene` (validate_scene, plus: alpha textures must be non-empty RGBA; throws
  // InputError) and builds + commits the Embree scene.
  // The scene's geometry and alpha textures are copied: `scene` may die afterwards. Throws
  // EmbreeError when Embree reports an error during construction.
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Length of the diagonal of the scene's vertex bounds, metres (0 for an empty scene). Sets
  // the scale of the self-intersection offset of shadow rays.
  float scene_scale() const;
  // Number of meshes of the source scene (valid geomIDs are below it).
  size_t mesh_count() const;
  // Number of meshes that were given alpha filter functions.
  size_t alpha_mesh_count() const;

  // For raytrace/*.cpp only: the committed RTCScene, as an opaque pointer.
  void* native_scene() const;
  // Throws EmbreeError if the device error callback recorded an error since the last call
  // (then clears it). `what` names the operation for the message.
  void throw_if_error(const char* what) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowlab
