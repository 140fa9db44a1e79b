// flicker: temporal stability of every technique along a path (the light moved by sub-texel
// steps, or the camera panned), against the ray-traced reference at the same GBuffer points
// (lab/flicker_run.h; docs/programs/flicker.md). Table on stdout; flicker.csv,
// flicker.json and flicker_worst.png (the worst row's frame differences above the
// reference's) in --out.
#include <cstdio>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_io.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/flicker_run.h"
#include "lab/memory_check.h"
#include "lab/provenance.h"
#include "techniques/registry/technique_spec.h"

using namespace shadowlab;

namespace {

const char* const kDefaultTechniques =
    "csm,cvsm,cesm,cevsm,cmsm,cpcss,tsm,tvsm,tesm,tevsm,tmsm,tpcss,dsm,dvsm,desm,devsm,dmsm,dpcss";

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("flicker", "[flags]");
    CommonOptions common;
    add_common_options(cl, common);
    set_default_size(cl, common, 512, 384, "not the scene camera's: every row renders every frame");
    FlickerConfig c;
    std::string techniques = kDefaultTechniques, path = "light-line";
    std::optional<double> step;
    int strip = 6;
    add_text(cl, "--techniques", "LIST", std::string("technique specs without res (default ") + kDefaultTechniques + ")", techniques);
    add_int_list(cl, "--resolutions", "LIST", "shadow-map resolutions (default 128,1024)", c.resolutions, 1, 8192);
    add_text(cl, "--path", "PATH", "light-line, light-circle (closes after the frames), light-jitter (a random offset of up to +-step per axis each frame) or camera-pan (default light-line)", path);
    add_int(cl, "--frames", "N", "frames along the path (default 32)", c.frames, 2, 100000);
    add_double(cl, "--step", "M", "metres per frame (default: a quarter of the finest map's texel at the camera target; camera-pan: a quarter pixel there)", step, 0.0, 1e6);
    add_int(cl, "--spp", "N", "reference samples per pixel (default 64; a hard reference when the light radius is 0)", c.spp, 1, 1 << 20);
    add_switch(cl, "--jitter", "also run each technique with texel snapping (the light position rounded to its map's texel size at the camera target)", c.jitter);
    add_int(cl, "--strip", "N", "frame differences in flicker_worst.png (default 6)", strip, 1, 64);
    if (!parse_command_line(cl, argc, argv)) return 0;
    c.path = parse_flicker_path(path, "--path");
    c.techniques = spec_list_items(techniques, "--techniques");
    if (step) c.step = *step;
    const Scene scene = scene_from_options(common);
    validate_flicker(scene, c);
    // Memory, before any work: the largest map and one run's images (check_run_memory), plus
    // two masks per row kept from frame to frame.
    {
      std::vector<TechniqueSpec> specs;
      size_t rows = 0;
      for (const std::string& t : c.techniques) {
        TechniqueSpec s = parse_technique_spec(t, "--techniques");
        if (s.name == "rt") {
          ++rows;
          continue;
        }
        for (int res : c.resolutions) {
          s.params["res"] = std::to_string(res);
          specs.push_back(s);
          rows += c.jitter ? 2 : 1;
        }
      }
      const uint64_t masks = uint64_t(rows + 1) * 2 * uint64_t(scene.camera.width) *
                             uint64_t(scene.camera.height) * sizeof(float);
      check_run_memory(scene, specs, max_memory_bytes(common), masks);
    }
    RunOutputs outputs(common.out, "--out");
    outputs.check_names({"flicker.csv", "flicker.json", "flicker_worst.png"});
    const FlickerResult r = measure_flicker(scene, c);
    std::printf("scene %s, %dx%d, path %s, %d frames, step %.6g m, reference %d spp, %d threads\n",
                scene.name.c_str(), scene.camera.width, scene.camera.height,
                flicker_path_name(c.path), c.frames, r.step, c.spp, thread_count());
    std::printf("%-24s %5s %9s %9s %9s %8s %6s %9s\n", "technique", "res", "change", "ref", "excess",
                "flips%", "worst", "worst_ex");
    std::string csv = "spec,technique,res,snapped,change,ref_change,excess,flip_share,worst_frame,worst_excess\n";
    nlohmann::json rows = nlohmann::json::array();
    const FlickerRow* worst = nullptr;
    for (const FlickerRow& row : r.rows) {
      const std::string label = row.technique + (row.snapped ? " snapped" : "");
      std::printf("%-24s %5d %9.5f %9.5f %9.5f %8.3f %6d %9.5f\n", label.c_str(), row.res, row.change,
                  row.ref_change, row.excess, 100.0 * row.flip_share, row.worst_frame, row.worst_excess);
      char line[512];
      std::snprintf(line, sizeof line, "\"%s\",\"%s\",%d,%d,%.9g,%.9g,%.9g,%.9g,%d,%.9g\n", row.spec.c_str(),
                    row.technique.c_str(), row.res, row.snapped ? 1 : 0, row.change, row.ref_change,
                    row.excess, row.flip_share, row.worst_frame, row.worst_excess);
      csv += line;
      rows.push_back({{"spec", row.spec}, {"technique", row.technique}, {"res", row.res},
                      {"snapped", row.snapped}, {"change", row.change}, {"ref_change", row.ref_change},
                      {"excess", row.excess}, {"flip_share", row.flip_share},
                      {"worst_frame", row.worst_frame}, {"worst_excess", row.worst_excess}});
      if (!worst || row.excess > worst->excess) worst = &row;
    }
    nlohmann::json j;
    j["provenance"] = provenance_json({&scene}, c.spp, 1);
    j["path"] = flicker_path_name(c.path);
    j["frames"] = c.frames;
    j["step_m"] = r.step;
    j["jitter"] = c.jitter;
    j["rows"] = rows;
    write_text_file(outputs.dir() + "/flicker.csv", csv);
    write_text_file(outputs.dir() + "/flicker.json", j.dump(2) + "\n");
    write_png_grey(outputs.dir() + "/flicker_worst.png", flicker_strip(scene, c, r.step, *worst, strip, 2));
    outputs.commit();
    std::printf("worst: %s (excess %.5f, frame %d); wrote %s/flicker.csv, flicker.json, flicker_worst.png "
                "(the technique's frame differences above the reference's, each row labelled)\n",
                worst->spec.c_str(), worst->excess, worst->worst_frame, common.out.c_str());
    return 0;
  });
}
