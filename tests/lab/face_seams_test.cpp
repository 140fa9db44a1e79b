// No seams at face boundaries: every cube and tetrahedron face boundary and corner is crossed
// by the receivers of lab/stability_cases.h's box room (all lit), and a control
// without the guard band shows that the test can fail.
#include <gtest/gtest.h>

#include "lab/stability_cases.h"
#include "techniques/pipeline/light_map.h"

namespace shadowlab {
namespace {

ShadowResult run(const std::string& spec, const Scene& scene, const GBuffer& g) {
  RunOptions opt;
  return run_technique(parse_technique_spec(spec, "--technique"), scene, g, opt);
}

TEST(FaceMaps, NoSeamsAcrossFaceBoundariesAndCorners) {
  const BoxRoom room = make_box_room();
  for (const char* spec : {"tsm:res=256", "tsm:res=256,pcf=5", "cvsm:res=256,blur=7",
                           "tvsm:res=256,blur=7", "cesm:res=256,blur=7", "tesm:res=256,blur=7",
                           "csm:res=256,pcf=5", "csm:res=256,pcf=5,seams=guard",
                           "tsm:res=256,pcf=5,seams=cross"}) {
    const ShadowResult r = run(spec, room.scene, room.g);
    float worst = 1.0f;
    for (size_t i = 0; i < room.g.pixel_count(); ++i)
      if (room.g.covered[i]) worst = std::min(worst, r.mask.data[i]);
    EXPECT_GE(worst, 0.99f) << spec;
  }
}

// The seam test can fail: the same blurred VSM without its guard band (the blur clamps at each
// face's edge and meets the neighbouring face's different depths) darkens boundary texels.
TEST(FaceMaps, WithoutGuardBandTheBlurLeavesSeams) {
  const BoxRoom room = make_box_room();
  const MapParams p = parse_map_params(parse_technique_spec("cvsm:res=256,blur=7", "t"),
                                       FaceLayoutKind::Cube, MapFilter::Variance, "t");
  LightMap map;
  map.layout = cube_layout(p.res, 0);
  render_light_map(room.scene, p, std::vector<bool>(6, true), map);
  filter_light_map(p, map);
  ImageF mask;
  lookup_light_map(room.scene, room.g, p, map, mask, nullptr);
  float worst = 1.0f;
  for (size_t i = 0; i < room.g.pixel_count(); ++i)
    if (room.g.covered[i]) worst = std::min(worst, mask.data[i]);
  EXPECT_LT(worst, 0.9f);
}

}  // namespace
}  // namespace shadowlab
