// stability: the stiff and extreme cases (docs/design.md §8) for every map-based technique, each row
// with its error against Embree hard shadows and its expected bound. Exit code 1 if a bound fails.
#include <cstdio>

#include "lab/cli.h"
#include "lab/stability_cases.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("stability", "[flags]");
    CommonOptions common;
    add_common_options(cl, common);
    mark_unused(cl, common_scene_flags(),
                "every case brings its own scene, light, view, size and technique (docs/design.md "
                "§8), and the table goes to stdout");
    if (!parse_command_line(cl, argc, argv)) return 0;
    const std::vector<StabilityRow> rows = run_stability_cases();
    std::printf("%s", stability_table(rows).c_str());
    size_t failed = 0;
    for (const StabilityRow& r : rows) failed += r.pass ? 0 : 1;
    std::printf("%zu rows, %zu outside their bound\n", rows.size(), failed);
    return failed == 0 ? 0 : 1;
  });
}
