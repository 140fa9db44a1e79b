// The rasterizer's camera pass against Embree primary rays through the same pixel centres.
#include <gtest/gtest.h>

#include <cmath>

#include "scenes/scene_library.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"

namespace shadowlab {
namespace {

TEST(RasterVsEmbree, DefaultSceneSamePrimitiveAndDepth) {
  Scene scene = make_builtin_scene("default");
  scene.camera.width = 256;
  scene.camera.height = 192;
  const GBuffer g = render_gbuffer(scene);
  EmbreeScene rt(scene);
  const PrimaryHits hits = primary_visibility(rt, scene.camera);
  size_t covered = 0, same = 0, depth_ok = 0, coverage_diff = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    const bool hit = hits.mesh_id[i] != kNoPrimitive;
    if (bool(g.covered[i]) != hit) ++coverage_diff;
    if (!g.covered[i]) continue;
    ++covered;
    if (g.mesh_id[i] == hits.mesh_id[i] && g.prim_id[i] == hits.prim_id[i]) {
      ++same;
      if (std::fabs(g.depth[i] - hits.depth[i]) <= 1e-4f * hits.depth[i]) ++depth_ok;
    }
  }
  ASSERT_GT(covered, g.pixel_count() * 9 / 10);  // a closed room: nearly every pixel covered
  EXPECT_GE(double(same), 0.995 * double(covered));
  EXPECT_GE(double(depth_ok), 0.995 * double(same));
  EXPECT_LE(double(coverage_diff), 0.005 * double(g.pixel_count()));
}

}  // namespace
}  // namespace shadowlab
