// Every technique of the registry (technique_list(): a new one is covered without a new line
// here) on the default, foliage and bunny-under-the-projector scenes: finite masks in [0, 1],
// texel indices where promised, and the same bytes at 1, 2 and 7 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "core/slide.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

Scene projector_scene() {
  Scene s = test::small_scene("bunny", 64, 48);
  Projector p = s.projector;
  p.slide = make_slide("spot", "test");
  set_projector(s, p, "test");
  return s;
}

TEST(Registry, EveryTechniqueIsFiniteInUnitRangeAndThreadCountIndependent) {
  const std::vector<std::pair<std::string, Scene>> scenes = {
      {"default", test::small_scene("default", 64, 48)},
      {"foliage", test::small_scene("foliage", 64, 48)},
      {"bunny+spot", projector_scene()}};
  const auto list = technique_list();
  ASSERT_GE(list.size(), 13u);  // rt + 4 filters × 3 layouts
  size_t runs = 0;
  for (const auto& [scene_name, scene] : scenes) {
    const GBuffer g = render_gbuffer(scene);
    for (const auto& [name, what] : list) {
      // The projector layout needs the projector; spp kept small for the ray tracer.
      if (name[0] == 'p' && !scene.projector.enabled) continue;
      const std::string spec = name == "rt"    ? "rt:spp=4"
                               : name == "rts" ? "rts:spp=2,denoise=atrous"
                                               : name + ":res=64";
      std::vector<ShadowResult> results;
      for (int threads : {1, 2, 7}) {
        set_thread_count(threads);
        results.push_back(test::run(spec, scene, g));
      }
      set_thread_count(2);
      const ShadowResult& r = results[0];
      ASSERT_EQ(r.mask.data.size(), g.pixel_count()) << spec << " on " << scene_name;
      for (const float v : r.mask.data)
        ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f) << spec << " on " << scene_name;
      for (size_t t = 1; t < results.size(); ++t) {
        EXPECT_EQ(std::memcmp(results[t].mask.data.data(), r.mask.data.data(), r.mask.data.size() * 4), 0)
            << spec << " on " << scene_name << ": mask differs between 1 thread and " << (t == 1 ? 2 : 7);
        EXPECT_EQ(results[t].texels.data, r.texels.data) << spec << " on " << scene_name;
      }
      ++runs;
    }
  }
  size_t projector_only = 0;
  for (const auto& entry : list) projector_only += entry.first[0] == 'p' ? 1 : 0;
  EXPECT_EQ(runs, 3 * list.size() - 2 * projector_only);  // p* only on the projector scene
}

}  // namespace
}  // namespace shadowlab
