// append_scene (scenes/scene_merge.h) re-bases every index: meshes' materials, and both the
// alpha and the colour texture of each material.
#include <gtest/gtest.h>

#include "scenes/scene_merge.h"

namespace shadowlab {
namespace {

TEST(SceneMerge, EveryIndexIsRebased) {
  Scene dst;
  dst.materials.push_back(Material{});
  dst.textures.push_back(ImageF(1, 1, 4, 0.25f));
  dst.meshes.push_back(Mesh{});
  Scene src;
  Material leaf;
  leaf.alpha_texture = 0;
  leaf.color_texture = 1;
  src.materials = {Material{}, leaf};
  src.textures = {ImageF(2, 1, 4, 0.5f), ImageF(3, 1, 4, 0.75f)};
  Mesh m;
  m.material = 1;
  src.meshes.push_back(m);
  append_scene(dst, src);
  ASSERT_EQ(dst.materials.size(), 3u);
  ASSERT_EQ(dst.textures.size(), 3u);
  ASSERT_EQ(dst.meshes.size(), 2u);
  EXPECT_EQ(dst.meshes[1].material, 2);
  const Material& moved = dst.materials[2];
  EXPECT_EQ(dst.textures[size_t(moved.alpha_texture)].width, 2);  // src's texture 0
  EXPECT_EQ(dst.textures[size_t(moved.color_texture)].width, 3);  // src's texture 1
  EXPECT_EQ(dst.materials[1].alpha_texture, -1);                  // none stays none
  EXPECT_EQ(dst.materials[1].color_texture, -1);
}

}  // namespace
}  // namespace shadowlab
