// raster_bench: times the rasterizer's three jobs on any scene — the depth-only cube shadow map
// (all 6 faces), the camera GBuffer pass and the cube-map lookup pass (pcf=1) — and prints the
// median, min and max over the repeats with the triangle and thread counts.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/parallel.h"
#include "core/timer.h"
#include "experiments/cli.h"
#include "raster/depth_kernels.h"
#include "raster/gbuffer_pass.h"
#include "techniques/light_map.h"

using namespace shadowlab;

namespace {

struct Stat {
  double median, min, max;
};

template <class Fn>
Stat time_it(int repeats, Fn&& fn) {
  fn();  // warm-up: first-touch allocation and thread start-up are not what is measured
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto s = std::chrono::steady_clock::now();
    fn();
    t.push_back(ms_since(s));
  }
  return {median(t), *std::min_element(t.begin(), t.end()), *std::max_element(t.begin(), t.end())};
}

void print(const char* what, const Stat& s) {
  std::printf("%-34s median %8.2f ms   min %8.2f   max %8.2f\n", what, s.median, s.min, s.max);
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("raster_bench", "[--scene S] [--res N] [--cull MODE] [flags]");
    CommonOptions common;
    add_common_options(cl, common);
    mark_unused(cl, {"--out", "--max-memory"}, "a benchmark writes no files and keeps one scene's buffers");
    int res = 1024, repeats = 15;
    std::string cull_name = "none", only;
    add_int(cl, "--res", "N", "cube face edge in texels (default 1024)", res, 1, 8192);
    add_text(cl, "--cull", "MODE", "none, back or front (default none)", cull_name);
    add_repeats(cl, repeats, 10, "after one untimed warm-up; min and max also printed");
    add_text(cl, "--only", "JOB", "cube, gbuffer or lookup: time one job (e.g. under callgrind)", only);
    if (!parse_command_line(cl, argc, argv)) return 0;
    CullMode cull = CullMode::None;
    if (cull_name == "back") cull = CullMode::Back;
    else if (cull_name == "front") cull = CullMode::Front;
    else if (cull_name != "none") throw InputError("--cull", "expected none, back or front, got '" + cull_name + "'");
    if (!only.empty() && only != "cube" && only != "gbuffer" && only != "lookup")
      throw InputError("--only", "expected cube, gbuffer or lookup, got '" + only + "'");
    auto want = [&](const char* job) { return only.empty() || only == job; };
    const Scene scene = scene_from_options(common);

    std::printf("scene %s: %zu triangles, %d threads, cube faces %d², camera %dx%d, cull %s, %d repeats, %s depth kernel\n",
                scene.name.c_str(), scene.triangle_count(), thread_count(), res, scene.camera.width,
                scene.camera.height, cull_name.c_str(), repeats, depth_kernel_name());
    // csm's pipeline stages with every face needed: render (stage 3) and the pcf=1 lookup.
    MapParams p = default_map_params(FaceLayoutKind::Cube, MapFilter::Depth);
    p.res = res;
    LightMap map;
    map.layout = map_layout(p, scene);
    const std::vector<bool> all(map.layout.faces.size(), true);
    auto cube = [&] { render_face_distances(scene, map.layout, all, map.dist, cull); };
    GBuffer g;
    auto gbuffer = [&] { render_gbuffer(scene, g); };
    ImageF mask;
    ImageU32 texels;
    auto lookup = [&] { lookup_light_map(scene, g, p, map, mask, &texels); };
    if (want("cube")) print("depth-only cube (6 faces)", time_it(repeats, cube));
    if (want("gbuffer")) print("camera GBuffer pass", time_it(repeats, gbuffer));
    if (want("lookup")) {
      if (!want("cube")) cube();  // the lookup needs a map and a GBuffer, untimed
      if (!want("gbuffer")) gbuffer();
      print("CSM lookup pass (pcf=1)", time_it(repeats, lookup));
    }
    return 0;
  });
}
