#pragma once
// Quality-versus-cost plot of a sweep: a self-contained SVG with two panels — total score and
// fidelity against shadow time on a log axis — and, when the points carry work counts, a third:
// total score against the map bytes touched (a cost that holds on any machine); the Pareto
// front of each panel.
#include <string>
#include <vector>

namespace shadowlab {

// One measured configuration as plotted.
struct PlotPoint {
  std::string label;     // text next to the marker, e.g. "CSM 512"
  std::string series;    // technique name, e.g. "csm"; one colour and marker per series
  double time_ms = 0.0;  // shadow time (map + lookup), ms; <= 0 is drawn at kPlotMinTimeMs
  double total = 0.0;    // total score, left panel's y
  double fidelity = 0.0; // fidelity score, middle panel's y
  double bytes = 0.0;    // map bytes touched (written + read, WorkCounts); <= 0: not in panel 3
  bool chosen = false;   // marked with a red square (the tuner's budget winners)
};

// Smallest time the log axis shows, ms: times <= 0 (a cached reference) are clamped to it.
constexpr double kPlotMinTimeMs = 1e-3;

// Per point: true iff no other point has cost <= and score >= with at least one strict
// (lower cost is better, higher score is better). Duplicates do not dominate each other, so
// both stay on the front. A point with a NaN cost or score is never on the front and dominates
// nothing. cost and score must have the same size.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& score);

// The SVG text: left panel y = total, middle panel y = fidelity, x = time_ms (log, decade
// ticks); a third panel y = total, x = bytes in MB (log), when any point has bytes > 0.
// Each panel's front (cost = time, score = that panel's y, over all points) is drawn as a
// staircase through its points in time order, and its points are ringed and labelled (each
// label where it overlaps no other, else left out); the other points are told apart by the
// legend (a colour and shape per series, wrapped onto as many lines as needed). Deterministic: every
// number has fixed precision. Points with a non-finite time or y are left out of that panel.
// score_name titles the total panels (the tuner plots its objective there).
std::string pareto_svg(const std::vector<PlotPoint>& points, const std::string& title,
                       const std::string& score_name = "total score");

// Writes pareto_svg(points, title) to path; throws InputError(path, "cannot write").
void write_pareto_svg(const std::string& path, const std::vector<PlotPoint>& points,
                      const std::string& title, const std::string& score_name = "total score");

}  // namespace shadowlab
