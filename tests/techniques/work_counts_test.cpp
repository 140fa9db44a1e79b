// The depth-compare lookups' work counts (WorkCounts::taps): one texel for a one-tap lookup;
// an N × N grid PCF with bilinear weights reads (N + 1)² texels; a Poisson kernel 2 × 2 texels
// per tap. Counted per pixel that looked the map up.
#include <gtest/gtest.h>

#include "test_scenes.h"

namespace shadowlab {
namespace {

TEST(WorkCounts, DepthCompareTapsPerPixelFollowTheKernel) {
  const Scene s = test::small_scene("default", 48, 36);
  const GBuffer g = render_gbuffer(s);
  struct Case {
    const char* spec;
    double taps;
  };
  for (const Case& c : {Case{"csm:res=64", 1.0}, Case{"csm:res=64,pcf=3", 16.0}, Case{"tsm:res=64,pcf=5", 36.0},
                        Case{"csm:res=64,pcf=3,pcf_kind=poisson,taps=8", 32.0}}) {
    const ShadowResult r = test::run(c.spec, s, g);
    ASSERT_GT(r.work.pixels_looked_up, 100u) << c.spec;
    EXPECT_EQ(r.work.taps_per_pixel(), c.taps) << c.spec;
    EXPECT_EQ(r.work.bytes_read, r.work.taps * 4) << c.spec;  // one float distance per texel
  }
}

}  // namespace
}  // namespace shadowlab
