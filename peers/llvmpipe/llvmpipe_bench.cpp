// llvmpipe_bench: shadowlab's depth-only cube shadow map against Mesa's llvmpipe on the same
// triangles, the same light and the same six 90° faces of res² texels (docs/llvmpipe.md).
// Both sides render every triangle into every face (no object culling, no face culling); each
// is warmed up twice, checked against the other (texel by texel), then
// timed in rounds that alternate the two, one render each, so that a slow phase of the machine
// falls on both. Prints each side's median, min and max and the ratio of the medians.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "egl_context.h"
#include "lab/cli.h"
#include "gl_depth_cube.h"
#include "raster/depth_kernels.h"
#include "techniques/pipeline/face_render.h"
#include "techniques/pipeline/light_faces.h"

using namespace shadowlab;

namespace {

template <class Fn>
double time_ms(Fn&& fn) {
  const auto s = std::chrono::steady_clock::now();
  fn();
  return ms_since(s);
}

// Texel by texel: the texels where one saw a surface and the other nothing, or both a surface
// at distances more than 1 mm + 0.1 % apart (the two depth encodings round differently).
// shadowlab stores |p − L| / far.
struct Agreement {
  size_t differ = 0, texels = 0;
};

Agreement compare(const FaceDistances& ours, float far,
                  const std::vector<std::vector<float>>& theirs) {
  Agreement a;
  for (size_t f = 0; f < theirs.size(); ++f)
    for (size_t i = 0; i < theirs[f].size(); ++i) {
      const double o = double(ours.distance[f][i]) * far, t = theirs[f][i];
      const bool ok = std::isfinite(o) ? std::isfinite(t) && std::abs(o - t) <= 1e-3 + 1e-3 * o
                                       : !std::isfinite(t);
      a.differ += !ok;
      ++a.texels;
    }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl =
        make_command_line("llvmpipe_bench", "[--scene S] [--res N] [--repeats N] [--threads N]");
    CommonOptions common;
    common.scene = "room100k";
    add_common_options(cl, common);
    mark_unused(cl, {"--out", "--max-memory"},
                "a benchmark writes no files and keeps one scene's buffers");
    int res = 1024, rounds = 11;
    add_int(cl, "--res", "N", "cube face edge in texels, both renderers (default 1024)", res, 16,
            4096);
    add_repeats(cl, rounds, 3,
                "rounds, each one render by shadowlab then one by llvmpipe, after two untimed "
                "renders each");
    if (!parse_command_line(cl, argc, argv)) return 0;

    // llvmpipe's rasterizer threads are --threads' count, so both sides use the same cores.
    const std::string threads = std::to_string(thread_count());
    if (const char* lp = std::getenv("LP_NUM_THREADS"); lp && *lp && threads != lp)
      throw InputError("LP_NUM_THREADS", std::string("is '") + lp +
                                             "', but llvmpipe_bench sets it to --threads' " +
                                             threads + " (unset it or give the same count)");
    setenv("LP_NUM_THREADS", threads.c_str(), 1);

    const Scene scene = scene_from_options(common);
    for (const Material& m : scene.materials)
      if (m.alpha_texture >= 0)
        throw InputError("--scene", "'" + scene.name + "' has alpha-tested materials (" + m.name +
                                        "), which the GL pass would draw opaque: give an "
                                        "opaque scene");

    // shadowlab: csm's render stage, every face needed, no guard band (6 × res² texels, as GL).
    const FaceLayout layout = cube_layout(res, 0);
    const std::vector<bool> all(layout.faces.size(), true);
    FaceDistances ours_out;
    auto ours = [&] { render_face_distances(scene, layout, all, ours_out); };

    EglContext context = make_llvmpipe_context();
    GlDepthCube gl = make_gl_depth_cube(scene, res);
    auto theirs = [&] { render_gl_depth_cube(gl); };

    std::printf("scene %s: %zu triangles, light (%g, %g, %g) near %g far %g\n",
                scene.name.c_str(), scene.triangle_count(), scene.light.position.x,
                scene.light.position.y, scene.light.position.z, scene.light.near,
                scene.light.far);
    std::printf("cube 6 x %d^2, %s threads each; shadowlab %s depth kernel; %s, %s\n", res,
                threads.c_str(), depth_kernel_name(), context.renderer.c_str(),
                context.version.c_str());

    for (int i = 0; i < 2; ++i) {
      ours();
      theirs();
    }
    const Agreement agree = compare(ours_out, scene.light.far, gl_radial_distances(gl));
    std::printf("check: %zu of the %zu texels differ between the two renders\n", agree.differ,
                agree.texels);
    // Texels whose centre lies on a silhouette edge may see different surfaces under the two
    // rasterization rules: a few per mille. A wrong light, face, orientation or range
    // disagrees almost everywhere.
    if (agree.differ * 100 > agree.texels)
      throw std::runtime_error("the two renders disagree on more than 1 % of the texels");

    std::vector<double> t_ours, t_theirs, ratios;
    for (int r = 0; r < rounds; ++r) {
      t_ours.push_back(time_ms(ours));
      t_theirs.push_back(time_ms(theirs));
      ratios.push_back(t_theirs.back() / t_ours.back());
    }
    const Stat a = stat_of(t_ours), b = stat_of(t_theirs), q = stat_of(ratios);
    std::printf("%-10s median %8.2f ms   min %8.2f   max %8.2f\n", "shadowlab", a.median, a.min,
                a.max);
    std::printf("%-10s median %8.2f ms   min %8.2f   max %8.2f\n", "llvmpipe", b.median, b.min,
                b.max);
    std::printf("llvmpipe / shadowlab: %.2fx (ratio of the medians; per-round ratios median "
                "%.2f, min %.2f, max %.2f, %d rounds)\n",
                b.median / a.median, q.median, q.min, q.max, rounds);
    destroy_gl_depth_cube(gl);
    destroy_context(context);
    return 0;
  });
}
