// metric: the Kluczek shadow metric of a test mask against a reference mask (EXR files).
#include <cstdio>

#include "core/image_io.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "experiments/cli.h"
#include "metric/metric_report.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    std::vector<FlagDef> defs = {
        {"--texels", "T.exr", "texel-index image of the test mask (detail score; else detail = 1)"},
        {"--json", "", "print one JSON object instead of the table"},
        {"--shadow-ms", "MS", "shadow time T_shadowed - T_unshadowed in ms (adds the performance score)"},
        {"--fps", "F", "target frame rate for the performance score (default 30)"},
        {"--repeats", "N", "time compute_metric over N runs and print the median on stderr"},
    };
    for (const FlagDef& d : common_flags())
      if (d.name != "--repeats") defs.push_back(d);
    mark_unused(defs, common_scene_flags(),
                "metric scores two images already rendered, and prints to stdout");
    const ParsedArgs args = parse_args(argc, argv, defs, 2);
    if (args.has("--help")) {
      std::printf("%s", usage_text("metric TEST.exr REF.exr [flags]", defs).c_str());
      return 0;
    }
    if (args.positional.size() != 2)
      throw InputError("metric", "expects two files: TEST.exr REF.exr (see --help)");
    const ImageF test = read_exr_mask(args.positional[0]);
    const ImageF ref = read_exr_mask(args.positional[1]);
    ImageU32 texels;
    if (args.has("--texels")) texels = read_exr_texels(args.get("--texels", ""));
    MetricWeights w;
    w.target_fps = args.get_double("--fps", 30.0, 1e-3, 1e6);
    Timings t;
    if (args.has("--shadow-ms")) t.shadowed_ms = args.get_double("--shadow-ms", 0.0, 0.0, 1e9);
    if (args.has("--threads")) set_thread_count(args.get_int("--threads", 1, 1, 1024));
    const ImageU32* tex = args.has("--texels") ? &texels : nullptr;
    const Timings* tim = args.has("--shadow-ms") ? &t : nullptr;
    MetricScratch scratch;
    MetricReport r;
    const int repeats = args.get_int("--repeats", 1, 1, 100000);
    const double ms = median_ms(repeats, [&] { r = compute_metric(test, ref, tex, tim, w, &scratch); });
    if (args.has("--repeats"))
      std::fprintf(stderr, "compute_metric %dx%d: median %.2f ms over %d runs, %d threads\n",
                   test.width, test.height, ms, repeats, thread_count());
    std::printf("%s\n", args.has("--json") ? metric_report_json(r).c_str()
                                            : metric_report_table(r).c_str());
    return 0;
  });
}
