// metric: the Kluczek shadow metric of a test mask against a reference mask (EXR files).
#include <cstdio>
#include <optional>

#include "core/image_io.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "metric/contour_image.h"
#include "metric/metric_report.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("metric", "TEST.exr REF.exr [flags]");
    std::string texels_path;
    bool json = false, texels_given = false;
    std::optional<double> shadow_ms;
    MetricWeights w;
    std::optional<int> repeats;
    add_text(cl, "--texels", "T.exr", "texel-index image of the test mask (detail score; else detail = 1)", texels_path, &texels_given);
    add_switch(cl, "--json", "print one JSON object instead of the table", json);
    std::string contours_path;
    bool contours_given = false;
    add_text(cl, "--contours", "OUT.png",
             "also write the reference's 10 %/90 % contours (black) and the test's (yellow) over "
             "red where the test is lighter, blue where darker (metric/contour_image.h)",
             contours_path, &contours_given);
    add_double(cl, "--shadow-ms", "MS", "shadow time T_shadowed - T_unshadowed in ms (adds the performance score)", shadow_ms, 0.0, 1e9);
    add_double(cl, "--fps", "F", "target frame rate for the performance score (default 30)", w.target_fps, 1e-3, 1e6);
    add_int(cl, "--repeats", "N", "timed runs of compute_metric, the median printed on stderr (default: not timed)", repeats, 1, 100000);
    CommonOptions common;
    add_common_options(cl, common);
    mark_unused(cl, common_scene_flags(),
                "metric scores two images already rendered, and prints to stdout");
    if (!parse_command_line(cl, argc, argv, 2)) return 0;
    if (cl.positional.size() != 2)
      throw InputError("metric", "expects two files: TEST.exr REF.exr (see --help)");
    const ImageF test = read_exr_mask(cl.positional[0]);
    const ImageF ref = read_exr_mask(cl.positional[1]);
    ImageU32 texels;
    if (texels_given) texels = read_exr_texels(texels_path);
    // The one output, checked against the inputs just read before the metric runs.
    RunOutputs outputs;
    const std::string contours_file =
        contours_given ? outputs.file("--contours", contours_path, ".png") : std::string();
    Timings t;
    if (shadow_ms) t.shadowed_ms = *shadow_ms;
    const ImageU32* tex = texels_given ? &texels : nullptr;
    const Timings* tim = shadow_ms ? &t : nullptr;
    MetricScratch scratch;
    MetricReport r;
    const double ms = median_ms(repeats.value_or(1), [&] { r = compute_metric(test, ref, tex, tim, w, &scratch); });
    if (repeats)
      std::fprintf(stderr, "compute_metric %dx%d: median %.2f ms over %d runs, %d threads\n",
                   test.width, test.height, ms, *repeats, thread_count());
    if (contours_given) write_png_rgb(contours_file, contour_comparison(test, ref));
    outputs.commit();
    std::printf("%s\n", json ? metric_report_json(r).c_str()
                                            : metric_report_table(r).c_str());
    return 0;
  });
}
