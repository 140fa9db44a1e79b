#pragma once
// Text forms of a MetricReport: one JSON object and a human-readable table.
#include <string>

#include "metric/shadow_metric.h"

namespace shadowlab {

// One JSON object on one line, keys in this order: c10 c50 c90 dark lit acne noise detail,
// performance (only when has_performance), fidelity aesthetics total ssim rmse psnr flip_mean.
// Numbers at full double precision (the shortest text that reads back to the same double); a
// non-finite value (none occurs in a report from compute_metric) is written as null.
std::string metric_report_json(const MetricReport& report);

// Every submetric, group and extra on its own line ("name  value  meaning"), ending in '\n'.
// Performance reads "n/a" without timings.
std::string metric_report_table(const MetricReport& report);

}  // namespace shadowlab
