// Analytic expectations every technique must meet.
#include <gtest/gtest.h>

#include "test_scenes.h"

namespace shadowlab {
namespace {

// A plane with nothing between it and the light is fully lit, by every technique.
TEST(Analytic, UnoccludedPlaneIsFullyLitByEveryTechnique) {
  const Scene scene = test::small_scene("plane", 96, 72);
  const GBuffer g = render_gbuffer(scene);
  size_t covered = 0;
  for (uint8_t c : g.covered) covered += c;
  ASSERT_GT(covered, g.pixel_count() / 2);
  for (const char* spec : {"csm:res=64", "csm:res=256,pcf=3", "csm:res=32,pcf=5", "rt:hard=1",
                           "rt:spp=16"}) {
    const ShadowResult r = test::run(spec, scene, g);
    for (size_t i = 0; i < g.pixel_count(); ++i)
      ASSERT_EQ(r.mask.data[i], 1.0f) << spec << " pixel " << i;
  }
}

// Receivers facing away from the light are 0 and empty pixels are 1, in every technique.
TEST(Analytic, FacingAwayIsZeroAndEmptyIsOne) {
  Scene scene = test::small_scene("plane", 64, 48);
  scene.light.position.y = -2.0f;  // below the floor: the floor faces away from it
  const GBuffer g = render_gbuffer(scene);
  for (const char* spec : {"csm:res=64", "rt:hard=1", "rt:spp=4"}) {
    const ShadowResult r = test::run(spec, scene, g);
    for (size_t i = 0; i < g.pixel_count(); ++i)
      ASSERT_EQ(r.mask.data[i], g.covered[i] ? 0.0f : 1.0f) << spec << " pixel " << i;
    if (!r.texels.empty()) {
      for (uint32_t t : r.texels.data) ASSERT_EQ(t, kNoTexel) << spec;
    }
  }
}

// A camera looking straight down a narrow cone below the light sees only points within 45° of
// straight down, so only the -Y face is needed (pcf=1) and only it is rendered.
TEST(Analytic, OnlyNeededCubeFacesAreRendered) {
  Scene scene = test::small_scene("plane", 64, 64);
  scene.camera.eye = vec3(0.0f, 1.9f, 0.0f);
  scene.camera.fov_y_deg = 60.0f;  // the floor is seen to ±1.1 m < 2 m: within 45° of -Y
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult r = test::run("csm:res=64", scene, g);
  EXPECT_EQ(r.faces_needed, 1);
  EXPECT_EQ(r.faces_rendered, 1);
  EXPECT_EQ(r.faces_total, 6);
}

}  // namespace
}  // namespace shadowlab
