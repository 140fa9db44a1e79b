// raster_bench: times the rasterizer's three jobs on any scene — the depth-only cube shadow map
// (all 6 faces), the camera GBuffer pass and the cube-map lookup pass (pcf=1) — and prints the
// median, min and max over the repeats with the triangle and thread counts. With --scaling it
// times each job at 1 thread and at --threads N instead, the two alternating repeat by repeat
// (docs/performance_history.md: the machines drift 10-20 % within minutes, so a ratio of two
// separate runs' medians measured the drift as much as the scaling), and prints the median of
// the per-repeat ratios.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/parallel.h"
#include "core/timer.h"
#include "lab/cli.h"
#include "raster/depth_kernels.h"
#include "raster/gbuffer_pass.h"
#include "techniques/pipeline/light_map.h"

using namespace shadowlab;

namespace {

template <class Fn>
Stat time_it(int repeats, Fn&& fn) {
  fn();  // warm-up: first-touch allocation and thread start-up are not what is measured
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto s = std::chrono::steady_clock::now();
    fn();
    t.push_back(ms_since(s));
  }
  return stat_of(t);
}

// One job's 1 -> n thread scaling: each repeat times the job at 1 thread, then at n, each after
// an untimed run at its count (a new thread count starts a new worker arena: core/parallel.h).
struct Scaling {
  Stat one, many, ratio;
};

template <class Fn>
Scaling time_scaling(int repeats, int n, Fn&& fn) {
  std::vector<double> t1, tn, r;
  for (int i = 0; i < repeats; ++i) {
    for (const int threads : {1, n}) {
      set_thread_count(threads);
      fn();
      const auto s = std::chrono::steady_clock::now();
      fn();
      (threads == 1 ? t1 : tn).push_back(ms_since(s));
    }
    r.push_back(t1.back() / tn.back());
  }
  set_thread_count(n);
  return {stat_of(t1), stat_of(tn), stat_of(r)};
}

void print_scaling(const char* what, int n, const Scaling& s) {
  std::printf("%-34s 1 -> %d threads: ratio median %.3f   min %.3f   max %.3f   (1 thread median %.2f ms, %d threads %.2f ms)\n",
              what, n, s.ratio.median, s.ratio.min, s.ratio.max, s.one.median, n, s.many.median);
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
    bool scaling = false;
    add_switch(cl, "--scaling",
               "time each job at 1 thread and at --threads N (N >= 2), alternating repeat by "
               "repeat, and print the median of the per-repeat ratios", scaling);
    if (!parse_command_line(cl, argc, argv)) return 0;
    if (scaling && thread_count() < 2)
      throw InputError("--scaling", "compares 1 thread with --threads N, and N is " +
                                        std::to_string(thread_count()) + " (give --threads 2 or more)");
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
    const int n = thread_count();
    auto job = [&](const char* what, auto&& fn) {
      if (scaling)
        print_scaling(what, n, time_scaling(repeats, n, fn));
      else
        print(what, time_it(repeats, fn));
    };
    if (want("cube")) job("depth-only cube (6 faces)", cube);
    if (want("gbuffer")) job("camera GBuffer pass", gbuffer);
    if (want("lookup")) {
      if (!want("cube")) cube();  // the lookup needs a map and a GBuffer, untimed
      if (!want("gbuffer")) gbuffer();
      job("CSM lookup pass (pcf=1)", lookup);
    }
    return 0;
  });
}
