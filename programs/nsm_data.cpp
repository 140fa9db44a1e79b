// nsm_data: the Neural Shadow Mapping data set (docs/programs/nsm_data.md): frames along camera
// and light trajectories over built-in scenes, each a crop window of its features, of 3
// perturbed copies' features and of the ray-traced reference at every light radius, one .nsmf
// file per frame in --out/frames/, and --out/manifest.json with the splits and the data set hash.
#include <cstdio>

#include "core/error.h"
#include "lab/cli.h"
#include "lab/nsm_data_command.h"
#include "lab/nsm_dataset.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("nsm_data", "[--scenes LIST] [--frames N] [--out DIR] [flags]");
    NsmDataCommand cmd;
    add_nsm_data_flags(cl, cmd);
    if (!parse_command_line(cl, argc, argv)) return 0;
    finish_nsm_data_command(cmd);
    const CommonOptions& common = cmd.common;
    const NsmDatasetParams& p = cmd.params;
    RunOutputs outputs(common.out, "--out");
    outputs.check_names({"manifest.json"});
    outputs.check_names({"frames"}, true);
    const std::vector<std::string> command =
        command_without(run_arguments(), {"--threads", "--out"});
    const uint64_t hash = write_nsm_dataset(p, outputs.dir(), command, stderr_is_terminal());
    outputs.commit();
    std::printf("wrote %d frames of %dx%d (%zu features x 4 copies, %zu reference planes) to %s/, "
                "data set hash %016llx\n",
                p.frames, p.crop_w, p.crop_h, p.features.size(), p.radii.size(), common.out.c_str(),
                static_cast<unsigned long long>(hash));
    return 0;
  });
}
