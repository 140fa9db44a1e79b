// Every vector table of the GBuffer resolve this CPU runs against its scalar oracle: identical
// bytes in every layer.
#include <gtest/gtest.h>

#include <cstring>

#include "scenes/scene_library.h"
#include "test_paths.h"
#include "raster/gbuffer_pass.h"
#include "core/isa.h"
#include "raster/gbuffer_resolve_simd.h"

namespace shadowlab {
namespace {

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(GBufferResolveSimd, MatchesScalarResolveBitForBit) {
  std::vector<Isa> isas;
  for (const Isa isa : cpu_isas())
    if (isa != Isa::scalar) isas.push_back(isa);
  if (isas.empty()) GTEST_SKIP() << "no vector set on this CPU";
  // foliage and bunny mix meshes in one row's 8 pixels (the mixed-triangle path).
  std::vector<std::string> names = {"default", "room100k", "plane", "foliage", "bunny"};
  // An OBJ with uvs and vertex normals.
  names.push_back(test::assets_dir() + "/palm_tree/palm_tree.obj");
  names.push_back("mixed");
  for (const std::string& name : names) {
    Scene scene = name == "mixed"                           ? make_builtin_scene("default")
                  : name.find(".obj") != std::string::npos ? make_obj_scene(name)
                                                            : make_builtin_scene(name);
    if (name == "mixed") {
      // Neighbouring meshes with and without vertex normals and uvs (which the resolve no
      // longer reads: they must not change its output): normals away from the mesh's first
      // vertex on every other mesh, uvs from x and z on every third.
      for (size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        mesh.normals.clear();
        mesh.uvs.clear();
        for (const vec3& p : mesh.positions) {
          const vec3 d = p - mesh.positions[0] + vec3(0.1f, 0.2f, 0.3f);
          if (m % 2 == 0) mesh.normals.push_back(glm::normalize(d));
          if (m % 3 == 0) mesh.uvs.push_back(vec2(p.x, p.z));
        }
      }
      ASSERT_GE(scene.meshes.size(), 6u);
    }
    scene.camera.width = 509;  // not a multiple of 8: runs end early at the right edge
    scene.camera.height = 300;
    GBuffer slow;
    render_gbuffer(scene, slow, nullptr, false);
    for (const Isa isa : isas) {
      const ScopedIsa scoped(isa);
      GBuffer fast;
      render_gbuffer(scene, fast, nullptr, true);
      EXPECT_TRUE(same(fast.position, slow.position)) << name << " " << isa_name(isa);
      EXPECT_TRUE(same(fast.geo_normal, slow.geo_normal)) << name << " " << isa_name(isa);
      // The shading attributes are deferred (core/gbuffer_shading.h) on both paths.
      EXPECT_FALSE(fast.has_shading_attributes() || slow.has_shading_attributes())
          << name << " " << isa_name(isa);
      EXPECT_TRUE(same(fast.depth, slow.depth)) << name << " " << isa_name(isa);
      EXPECT_TRUE(same(fast.mesh_id, slow.mesh_id)) << name << " " << isa_name(isa);
      EXPECT_TRUE(same(fast.prim_id, slow.prim_id)) << name << " " << isa_name(isa);
      EXPECT_TRUE(same(fast.covered, slow.covered)) << name << " " << isa_name(isa);
    }
  }
}

}  // namespace
}  // namespace shadowlab
