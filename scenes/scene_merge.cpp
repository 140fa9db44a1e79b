#include "scenes/scene_merge.h"

namespace shadowlab {

void append_scene(Scene& dst, Scene src) {
  const int material_base = int(dst.materials.size());
  const int texture_base = int(dst.textures.size());
  for (Material& m : src.materials) {
    if (m.alpha_texture >= 0) m.alpha_texture += texture_base;
    if (m.color_texture >= 0) m.color_texture += texture_base;
    dst.materials.push_back(std::move(m));
  }
  for (ImageF& t : src.textures) dst.textures.push_back(std::move(t));
  for (Mesh& m : src.meshes) {
    m.material += material_base;
    dst.meshes.push_back(std::move(m));
  }
}

}  // namespace shadowlab
