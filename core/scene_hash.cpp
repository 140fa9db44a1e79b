#include "core/scene_hash.h"

#include <fmt/format.h>

#include "core/hash.h"

namespace shadowlab {
namespace {

void image(Fnv1a& f, const ImageF& img) {
  f.u64(uint64_t(img.width));
  f.u64(uint64_t(img.height));
  f.u64(uint64_t(img.channels));
  f.array(img.data);
}

}  // namespace

std::string scene_hash(const Scene& s) {
  Fnv1a f;
  f.u64(s.meshes.size());
  for (const Mesh& m : s.meshes) {
    f.array(m.positions);
    f.array(m.normals);
    f.array(m.uvs);
    f.array(m.indices);
    f.u64(uint64_t(int64_t(m.material)));
  }
  f.u64(s.materials.size());
  for (const Material& m : s.materials) {
    f.v3(m.albedo);
    f.u64(uint64_t(int64_t(m.alpha_texture)));
    f.f32(m.alpha_cutoff);
    f.u64(uint64_t(int64_t(m.color_texture)));
    f.v3(m.color_factor);
  }
  f.u64(s.textures.size());
  for (const ImageF& t : s.textures) image(f, t);
  f.v3(s.light.position);
  f.f32(s.light.radius);
  f.f32(s.light.near);
  f.f32(s.light.far);
  const Projector& p = s.projector;
  f.u64(uint64_t(p.enabled));
  if (p.enabled) {
    f.v3(p.position);
    f.v3(p.direction);
    f.v3(p.up);
    f.f32(p.fov_y_deg);
    f.f32(p.aspect);
    image(f, p.slide.rgb);
  }
  const Camera& c = s.camera;
  f.v3(c.eye);
  f.v3(c.target);
  f.v3(c.up);
  f.f32(c.fov_y_deg);
  f.f32(c.near);
  f.f32(c.far);
  f.u64(uint64_t(c.width));
  f.u64(uint64_t(c.height));
  f.u64(s.seed);
  return fmt::format("{:016x}", f.h);
}

}  // namespace shadowlab
