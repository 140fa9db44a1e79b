#pragma once
// The resolution sweep behind programs/resolution_sweep: every technique at every
// resolution against the ray-traced reference, scored by the shadow metric, with timings.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "util/pareto_plot.h"
#include "metric/shadow_metric.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

struct SweepConfig {
  std::vector<std::string> techniques = {"csm"};  // specs without res (res is swept)
  std::vector<int> resolutions = {128, 256, 512, 1024};
  int spp = 256;                // reference samples per pixel
  int repeats = 5;              // timing repeats (median)
  std::string cache_dir;        // reference cache; empty = none
  std::string out_dir;          // masks (EXR + PNG) per row when non-empty
  bool progress = false;        // progress line with ETA on stderr
  double target_fps = 30.0;     // performance score T_ref = 1/fps
  uint64_t max_memory = 0;      // refuse runs estimated above this many bytes (0: what is available)
  float ambient = 0.1f;         // ambient level of the shaded images (techniques/shading/scene_shading.h)
  bool shaded_sheet = false;    // contact sheet of shaded images (--sheet shaded), else masks
  bool flip_map = false;        // write each row's FLIP error map of the shaded image (--flip-map)
  int shard = 0, shards = 1;    // run only rows with index mod shards == shard (--shard i/N)
};

struct SweepRow {
  std::string label;            // "CSM 512", "RT 256spp"
  std::string technique;        // registry name of the spec, e.g. "csm" ("rt" for the reference)
  std::string spec;             // canonical spec text
  int res = 0;                  // 0 for the reference
  size_t index = 0;             // technique index × resolutions + resolution index (--shard)
  ShadowResult result;
  MetricReport report;
  ImageF shaded_cell;           // the shaded image box-downscaled to the contact sheet's cell
  double flip_shaded = 0.0;     // mean LDR-FLIP of the shaded image against the reference's
};

struct SweepResult {
  std::string scene;
  int width = 0, height = 0;
  double camera_ms = 0.0;       // unshadowed camera pass, median
  SweepRow reference;
  std::vector<SweepRow> rows;
  nlohmann::json provenance;    // lab/provenance.h; in every file the sweep writes
  size_t rows_total = 0;        // rows of the whole sweep (all shards)
  int shard = 0, shards = 1;
};

SweepResult run_resolution_sweep(const Scene& scene, const SweepConfig& config);

// Table in the layout of Kluczek's Table I plus time, RP and total; reference row first.
std::string sweep_table(const SweepResult& result);
void write_sweep_csv(const std::string& path, const SweepResult& result);
// One CSV of several scenes' sweeps (a suite): the same columns, the first one `scene`.
void write_sweep_csv(const std::string& path, const std::vector<const SweepResult*>& results);
// The suite summary: per technique and setting (row), each scene's fidelity, then total, with
// the mean and the worst over the scenes and the scene of the worst. Every result must have
// the same rows (the same techniques and resolutions).
std::string suite_table(const std::vector<SweepResult>& results);
void write_sweep_json(const std::string& path, const SweepResult& result);
// The object write_sweep_json writes.
nlohmann::json sweep_json(const SweepResult& result);

// Reads sweep_json's output back (the rows' scores, times and work counts; no images): how
// merge combines the shards of `resolution_sweep --shard i/N`. `where` names the file in errors.
SweepResult sweep_from_json(const nlohmann::json& j, const std::string& where);
// Combines shard results: the same scene, settings and provenance, every row index present
// exactly once; throws InputError naming the file otherwise.
SweepResult merge_sweep_shards(const std::vector<nlohmann::json>& shards,
                               const std::vector<std::string>& paths);

// One plot point per technique row (not the reference: compared with itself and without
// timings, its total is not on the rows' scale): series = technique, time = shadow ms.
std::vector<PlotPoint> sweep_plot_points(const SweepResult& result);
// The contact sheet: one row per config.techniques entry, one column per config.resolutions
// entry (both in config order), the reference as the first column; cells are the masks, or the
// shaded images with config.shaded_sheet, each with its total score under it, labelled
// (sweep_caption).
ImageF sweep_contact_sheet(const SweepResult& result, const SweepConfig& config);
// The caption under a row's cell: "total 0.834" (the score named, 3 decimals).
std::string sweep_caption(const SweepRow& row);

}  // namespace shadowlab
