// Output never depends on the thread count: camera pass, cube map and the Embree reference.
#include <gtest/gtest.h>

#include <cstring>

#include "core/parallel.h"
#include "scenes/scene_library.h"
#include "test_paths.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Determinism, OneTwoAndSevenThreadsGiveIdenticalBytes) {
  const Scene scene = test::small_scene("default", 200, 150);
  struct Out {
    GBuffer g;
    ShadowResult csm, soft;
    std::vector<ShadowResult> family;
  };
  std::vector<Out> outs;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    Out o;
    o.g = render_gbuffer(scene);
    o.csm = test::run("csm:res=256,pcf=3", scene, o.g);
    o.soft = test::run("rt:spp=16", scene, o.g);
    // Every filter on every layout (the projector's below), the SIMD paths included.
    for (const char* spec : {"tsm:res=128,pcf=3", "cvsm:res=128,slope_moment=1,maxdepth_eps=0.02",
                             "tvsm:res=128,fp32=1", "cesm:res=128,c=300", "tesm:res=64,normal=1",
                             "csm:res=256", "tsm:res=128", "csm:res=128,pcf=5,seams=guard",
                             "tsm:res=128,pcf=3,seams=cross", "cvsm:res=128,bleed=0.2", "tesm:res=128",
                             "csm:res=128,pcf=5,pcf_kind=poisson", "tsm:res=128,pcf=3,pcf_kind=poisson,taps=8",
                             "cevsm:res=128,moments=4,bleed=0.1", "tmsm:res=128,variant=hausdorff",
                             "cmsm:res=128,quantize16=1", "cpcss:res=128,light_size=0.1",
                             "tpcss:res=128,light_size=0.2,rpdb=0", "csm:res=128,pcf=3,rpdb=1",
                             "tsm:res=128,pcf=5,pcf_kind=poisson,rpdb=1", "dsm:res=128,tess=8",
                             "dvsm:res=128", "dpcss:res=128,light_size=0.1"})
      o.family.push_back(test::run(spec, scene, o.g));
    outs.push_back(std::move(o));
  }
  set_thread_count(2);
  for (size_t i = 1; i < outs.size(); ++i) {
    EXPECT_TRUE(same_bytes(outs[0].g.position, outs[i].g.position));
    EXPECT_TRUE(same_bytes(outs[0].g.prim_id, outs[i].g.prim_id));
    EXPECT_TRUE(same_bytes(outs[0].g.depth, outs[i].g.depth));
    EXPECT_TRUE(same_bytes(outs[0].csm.mask.data, outs[i].csm.mask.data));
    EXPECT_TRUE(same_bytes(outs[0].csm.texels.data, outs[i].csm.texels.data));
    EXPECT_TRUE(same_bytes(outs[0].soft.mask.data, outs[i].soft.mask.data));
    for (size_t k = 0; k < outs[0].family.size(); ++k) {
      EXPECT_TRUE(same_bytes(outs[0].family[k].mask.data, outs[i].family[k].mask.data)) << k;
      EXPECT_TRUE(same_bytes(outs[0].family[k].texels.data, outs[i].family[k].texels.data)) << k;
    }
  }
}

// Alpha discard (foliage) and the projector path, at 1, 2 and 7 threads.
TEST(Determinism, FoliageAndProjectorAreThreadCountIndependent) {
  const Scene foliage = test::small_scene("foliage", 160, 120);
  Scene bunny = test::small_scene("bunny", 160, 120);
  Projector p = bunny.projector;
  p.slide = make_slide("grid:amp=1,freq=4", "test");
  set_projector(bunny, p, "test");
  std::vector<std::vector<std::vector<float>>> outs;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    std::vector<std::vector<float>> o;
    const GBuffer g = render_gbuffer(foliage);
    o.push_back(std::vector<float>(g.depth));
    for (const char* spec : {"csm:res=256,pcf=3", "tsm:res=128", "cvsm:res=128"})
      o.push_back(test::run(spec, foliage, g).mask.data);
    const GBuffer gb = render_gbuffer(bunny);
    for (const char* spec : {"psm:res=256,pcf=3,depth=8cubic", "psm:res=256", "pvsm:res=128", "pesm:res=128"})
      o.push_back(test::run(spec, bunny, gb).mask.data);
    outs.push_back(std::move(o));
  }
  set_thread_count(2);
  for (size_t i = 1; i < outs.size(); ++i)
    for (size_t k = 0; k < outs[0].size(); ++k) EXPECT_TRUE(same_bytes(outs[0][k], outs[i][k])) << k;
}

}  // namespace
}  // namespace shadowlab
