// The lookups' work counts (WorkCounts::taps and bytes_read), per pixel that looked the map up:
// depth compare reads one texel for a one-tap lookup, (N + 1)² for an N × N grid PCF with
// bilinear weights and 2 × 2 per Poisson tap, 4 bytes each; the moment maps read the 2 × 2
// texels of a bilinear tap, each its stored moments (VSM 2 floats, MSM 4 floats or, quantized,
// 4 × 16 bits).
#include <gtest/gtest.h>

#include "test_scenes.h"

namespace shadowlab {
namespace {

TEST(WorkCounts, TapsAndBytesPerPixelFollowTheKernelAndTheStoredValues) {
  const Scene s = test::small_scene("default", 48, 36);
  const GBuffer g = render_gbuffer(s);
  struct Case {
    const char* spec;
    double taps;
    uint64_t bytes_per_tap;
  };
  for (const Case& c : {Case{"csm:res=64", 1.0, 4}, Case{"csm:res=64,pcf=3", 16.0, 4},
                        Case{"tsm:res=64,pcf=5", 36.0, 4}, Case{"csm:res=64,pcf=3,pcf_kind=poisson,taps=8", 32.0, 4},
                        Case{"cvsm:res=64", 4.0, 8}, Case{"cmsm:res=64", 4.0, 16},
                        Case{"cmsm:res=64,quantize16=1", 4.0, 8}}) {
    const ShadowResult r = test::run(c.spec, s, g);
    ASSERT_GT(r.work.pixels_looked_up, 100u) << c.spec;
    EXPECT_EQ(r.work.taps_per_pixel(), c.taps) << c.spec;
    EXPECT_EQ(r.work.bytes_read, r.work.taps * c.bytes_per_tap) << c.spec;
  }
}

}  // namespace
}  // namespace shadowlab
