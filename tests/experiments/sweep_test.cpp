// The sweep's scores behave as the paper's do: they rise with shadow-map resolution.
#include <gtest/gtest.h>

#include "core/scene_library.h"
#include "experiments/sweep.h"

namespace shadowlab {
namespace {

TEST(Sweep, FidelityAndDetailRiseWithResolution) {
  Scene scene = make_builtin_scene("default");
  scene.camera.width = 256;
  scene.camera.height = 192;
  SweepConfig c;
  c.resolutions = {32, 128, 512};
  c.spp = 16;
  c.repeats = 1;
  const SweepResult r = run_resolution_sweep(scene, c);
  ASSERT_EQ(r.rows.size(), 3u);
  // The reference compared with itself is perfect in every submetric.
  const MetricReport& ref = r.reference.report;
  for (double v : {ref.c10, ref.c50, ref.c90, ref.dark, ref.lit, ref.acne, ref.noise, ref.detail})
    EXPECT_DOUBLE_EQ(v, 1.0);
  // Finer maps: more texels per pixel (detail) and a better match (fidelity).
  EXPECT_LT(r.rows[0].report.detail, r.rows[1].report.detail);
  EXPECT_LT(r.rows[1].report.detail, r.rows[2].report.detail);
  EXPECT_LT(r.rows[0].report.fidelity, r.rows[2].report.fidelity);
  for (const SweepRow& row : r.rows) {
    EXPECT_GT(row.result.shadow_ms(), 0.0);
    EXPECT_GE(row.result.faces_rendered, 1);
    EXPECT_LE(row.result.faces_rendered, 6);
  }
}

}  // namespace
}  // namespace shadowlab
