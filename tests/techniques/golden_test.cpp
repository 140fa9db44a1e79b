// Golden-image test of a small cube-shadow-map mask.
//
// The golden file tests/golden/csm_default_160x120.exr was reviewed by eye against the Embree
// reference of the same view (shadows of the box, sphere, pole, table and ramp in place; no
// acne on the floor). To regenerate after an intended change, run
//   SHADOWLAB_UPDATE_GOLDEN=1 ./build/tests/test_techniques --gtest_filter=Golden.*
// then review the new PNG beside it (tests/golden/csm_default_160x120.png) before committing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "../test_paths.h"
#include "core/image_io.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

TEST(Golden, SmallCubeMapMaskMatchesReviewedImage) {
  const Scene scene = test::small_scene("default", 160, 120);
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult r = test::run("csm:res=128,pcf=3", scene, g);
  const std::string golden = test::source_path("tests/golden/csm_default_160x120.exr");
  if (const char* update = std::getenv("SHADOWLAB_UPDATE_GOLDEN"); update && *update == '1') {
    write_exr_mask(golden, r.mask);
    write_png_grey(test::source_path("tests/golden/csm_default_160x120.png"), r.mask);
    GTEST_SKIP() << "golden image rewritten: review it before committing";
  }
  const ImageF expected = read_exr_mask(golden);
  ASSERT_EQ(expected.width, r.mask.width);
  ASSERT_EQ(expected.height, r.mask.height);
  // Tolerance: another compiler may round a few lookups differently, which moves single
  // edge pixels; a real change moves many.
  ImageF diff(expected.width, expected.height, 1, 0.0f);
  size_t differing = 0;
  float max_diff = 0.0f;
  for (size_t i = 0; i < diff.data.size(); ++i) {
    diff.data[i] = std::fabs(expected.data[i] - r.mask.data[i]);
    max_diff = std::max(max_diff, diff.data[i]);
    differing += diff.data[i] > 1e-3f;
  }
  const double share = double(differing) / double(diff.data.size());
  if (share > 0.002) {
    const std::string path = test::binary_path("golden_diff_csm_default_160x120.png");
    write_png_grey(path, diff);
    ADD_FAILURE() << share * 100 << " % of pixels differ (max " << max_diff
                  << "); difference image: " << path;
  }
}

}  // namespace
}  // namespace shadowlab
