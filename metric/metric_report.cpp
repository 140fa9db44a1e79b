#include "metric/metric_report.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace shadowlab {
namespace {

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  if (v == 0.0) v = 0.0;  // print −0 as 0
  return fmt::format("{:.6f}", v);
}

}  // namespace

std::string metric_report_json(const MetricReport& r) {
  // nlohmann-json (ordered: the documented key order), full double precision; a non-finite
  // value is null.
  std::vector<std::pair<const char*, double>> fields = {
      {"c10", r.c10}, {"c50", r.c50},   {"c90", r.c90},     {"dark", r.dark},
      {"lit", r.lit}, {"acne", r.acne}, {"noise", r.noise}, {"detail", r.detail}};
  if (r.has_performance) fields.emplace_back("performance", r.performance);
  fields.insert(fields.end(), {{"fidelity", r.fidelity},
                               {"aesthetics", r.aesthetics},
                               {"total", r.total},
                               {"ssim", r.ssim},
                               {"rmse", r.rmse},
                               {"psnr", r.psnr},
                               {"flip_mean", r.flip_mean}});
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [key, v] : fields)
    j[key] = std::isfinite(v) ? nlohmann::ordered_json(v == 0.0 ? 0.0 : v) : nlohmann::ordered_json(nullptr);
  return j.dump();
}

std::string metric_report_table(const MetricReport& r) {
  struct Line {
    const char* name;
    std::string value;
    const char* meaning;
  };
  const std::vector<Line> lines = {
      {"c10", number(r.c10), "contour match at blurred level 0.1"},
      {"c50", number(r.c50), "contour match at blurred level 0.5"},
      {"c90", number(r.c90), "contour match at blurred level 0.9"},
      {"dark", number(r.dark), "dark-area coverage"},
      {"lit", number(r.lit), "lit-area coverage"},
      {"acne", number(r.acne), "Roberts-cross roughness in the lit region"},
      {"noise", number(r.noise), "Roberts-cross roughness in the dark region"},
      {"detail", number(r.detail), "1 / RMS pixels per shadow-map texel"},
      {"performance", r.has_performance ? number(r.performance) : std::string("n/a"),
       r.has_performance ? "1 / (1 + shadow time / frame time)" : "no timings given"},
      {"fidelity", number(r.fidelity), "mean of c10 c50 c90 dark lit"},
      {"aesthetics", number(r.aesthetics), "mean of acne noise"},
      {"total", number(r.total), "weighted mean of the groups"},
      {"ssim", number(r.ssim), "mean SSIM, unblurred masks"},
      {"rmse", number(r.rmse), "RMSE, unblurred masks"},
      {"psnr", number(r.psnr), "dB, capped at 100"},
      {"flip_mean", number(r.flip_mean), "mean LDR-FLIP, masks as grey images (0 = same)"},
      {"blur", std::to_string(r.blur_size) + "x" + std::to_string(r.blur_size),
       "box blur before contours and coverage"},
  };
  std::string out;
  for (const Line& l : lines) {
    out += fmt::format("{:<12} {:>11}  {}\n", l.name, l.value, l.meaning);
  }
  return out;
}

}  // namespace shadowlab
