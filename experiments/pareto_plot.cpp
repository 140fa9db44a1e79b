#include "experiments/pareto_plot.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/output_file.h"

namespace shadowlab {

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& score) {
  SL_CHECK_EQ(cost.size(), score.size());
  const size_t n = cost.size();
  std::vector<bool> front(n, false);
  // O(n²) is plenty for a sweep (n < 100) and leaves nothing to get wrong about tie order.
  for (size_t i = 0; i < n; ++i) {
    if (std::isnan(cost[i]) || std::isnan(score[i])) continue;
    bool dominated = false;
    for (size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || std::isnan(cost[j]) || std::isnan(score[j])) continue;
      dominated = cost[j] <= cost[i] && score[j] >= score[i] &&
                  (cost[j] < cost[i] || score[j] > score[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

namespace {

// Page layout, SVG px: a title line, a legend line, then two or three plot areas side by side
// with room on their left for y tick labels and below for x tick labels and the axis title.
constexpr double kPanelStep = 465.0, kHeight = 450.0;
constexpr double kPlotTop = 78.0, kPlotHeight = 300.0, kPlotWidth = 370.0;
constexpr double kPlotLeft[3] = {80.0, 80.0 + kPanelStep, 80.0 + 2.0 * kPanelStep};
constexpr double kMarkerRadius = 4.5;
constexpr double kRingRadius = 8.0;
// Colour-blind-friendly-ish, distinct in grey print too; series beyond 8 reuse with a new shape.
constexpr const char* kPalette[] = {"#1f5fa8", "#d1495b", "#2a9d4a", "#e08a00",
                                    "#7b4fb0", "#128c8c", "#8c564b", "#555555"};
constexpr int kPaletteSize = int(sizeof kPalette / sizeof kPalette[0]);
constexpr int kShapeCount = 5;  // circle, square, triangle up, diamond, triangle down

// fmt-style append; every number in the SVG goes through a fixed-precision format.
template <class... Args>
void add(std::string& s, fmt::format_string<Args...> f, Args&&... args) {
  fmt::format_to(std::back_inserter(s), f, std::forward<Args>(args)...);
}

// Marker shape of series k: cycles faster than the palette, so series 8 (colour 0 again) gets
// a different shape from series 0.
int shape_of(int k) { return k / kPaletteSize + k; }

// XML text/attribute escaping; control characters XML 1.0 forbids become '?'.
std::string escape_xml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') ? '?' : c;
    }
  }
  return out;
}

// Mapping of one panel's data to SVG px: x = log10(cost) over whole decades, y linear.
struct Panel {
  double left = 0.0;          // plot area's left edge, px
  int decade_lo = 0;          // x axis spans 10^decade_lo .. 10^decade_hi ms
  int decade_hi = 1;
  double y_lo = 0.0, y_hi = 1.0;  // score range shown (padded)
  double px(double time_ms) const {
    const double t = std::log10(std::max(time_ms, kPlotMinTimeMs));
    return left + (t - decade_lo) / double(decade_hi - decade_lo) * kPlotWidth;
  }
  double py(double v) const { return kPlotTop + (y_hi - v) / (y_hi - y_lo) * kPlotHeight; }
};

// Whole decades covering the finite times (clamped to the floor); at least one decade, so a
// range inside one decade (2–8 ms) still gets ticks at both ends (1 and 10). The epsilon keeps
// an exact power of ten (log10 may be off by an ulp) from adding an empty decade.
void time_decades(const std::vector<double>& times, int& lo, int& hi) {
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  for (double t : times) {
    if (!std::isfinite(t)) continue;
    t = std::max(t, kPlotMinTimeMs);
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
  }
  if (!(t_min <= t_max)) {  // no finite time: show 1–10 ms
    lo = 0;
    hi = 1;
    return;
  }
  lo = int(std::floor(std::log10(t_min) + 1e-9));
  hi = int(std::ceil(std::log10(t_max) - 1e-9));
  if (hi <= lo) hi = lo + 1;
}

// Score range: data min..max widened to at least 0.01 (so 3-decimal ticks stay distinct) and
// padded by 8% each side so markers and rings sit inside the frame.
void score_range(const std::vector<double>& values, double& lo, double& hi) {
  double v_min = std::numeric_limits<double>::infinity(), v_max = -v_min;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    v_min = std::min(v_min, v);
    v_max = std::max(v_max, v);
  }
  if (!(v_min <= v_max)) {
    v_min = 0.0;
    v_max = 1.0;
  }
  if (v_max - v_min < 0.01) {
    const double mid = 0.5 * (v_min + v_max);
    v_min = mid - 0.005;
    v_max = mid + 0.005;
  }
  const double pad = 0.08 * (v_max - v_min);
  lo = v_min - pad;
  hi = v_max + pad;
}

// Tick step of 1, 2 or 5 × 10^k giving about five ticks over the span.
double nice_step(double span) {
  const double raw = span / 5.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  return (norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0) * mag;
}

std::string decade_label(int d) {
  return d >= 0 ? fmt::format("{:.0f}", std::pow(10.0, d))
                : fmt::format("{:.{}f}", std::pow(10.0, d), -d);
}

// Marker of a series at (x, y): shape by series index, filled with its colour.
void marker(std::string& s, const char* cls, int shape, double x, double y, const char* colour) {
  const double r = kMarkerRadius;
  switch (shape % kShapeCount) {
    case 0:
      add(s, "<circle class=\"{}\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n", cls, x, y,
          r, colour);
      break;
    case 1:
      add(s, "<rect class=\"{}\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>\n",
          cls, x - r * 0.85, y - r * 0.85, r * 1.7, r * 1.7, colour);
      break;
    case 2:
      add(s, "<path class=\"{}\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\" fill=\"{}\"/>\n", cls, x,
          y - r * 1.1, x + r, y + r * 0.8, x - r, y + r * 0.8, colour);
      break;
    case 3:
      add(s, "<path class=\"{}\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\" fill=\"{}\"/>\n",
          cls, x, y - r * 1.2, x + r, y, x, y + r * 1.2, x - r, y, colour);
      break;
    default:
      add(s, "<path class=\"{}\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\" fill=\"{}\"/>\n", cls, x,
          y + r * 1.1, x + r, y - r * 0.8, x - r, y - r * 0.8, colour);
  }
}

// Frame, grid, ticks and axis titles of one panel.
void draw_axes(std::string& s, const Panel& p, const char* y_title, const char* x_title) {
  const double bottom = kPlotTop + kPlotHeight, right = p.left + kPlotWidth;
  add(s, "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"#fafafa\" "
         "stroke=\"#333\" stroke-width=\"1\"/>\n", p.left, kPlotTop, kPlotWidth, kPlotHeight);
  // x: a labelled grid line per decade, short unlabelled ticks at 2..9 × 10^d.
  for (int d = p.decade_lo; d <= p.decade_hi; ++d) {
    const double x = p.px(std::pow(10.0, d));
    add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#ddd\"/>\n", x,
        kPlotTop, x, bottom);
    add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\"/>\n", x, bottom,
        x, bottom + 6.0);
    add(s, "<text class=\"xtick\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"11\" text-anchor=\"middle\">{}</text>\n",
        x, bottom + 19.0, decade_label(d).c_str());
    if (d == p.decade_hi) break;
    for (int m = 2; m <= 9; ++m) {
      const double xm = p.px(m * std::pow(10.0, d));
      add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\"/>\n", xm,
          bottom, xm, bottom + 3.0);
    }
  }
  // y: ticks at multiples of a nice step, 2 decimals unless the step needs 3.
  const double step = nice_step(p.y_hi - p.y_lo);
  const int decimals = step >= 0.01 - 1e-12 ? 2 : 3;
  const long first = long(std::ceil(p.y_lo / step - 1e-9));
  for (long k = first;; ++k) {
    double v = double(k) * step;
    if (v > p.y_hi + 1e-9 * step) break;
    if (std::fabs(v) < 1e-6 * step) v = 0.0;  // no "-0.00"
    const double y = p.py(v);
    add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#ddd\"/>\n", p.left, y,
        right, y);
    add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\"/>\n",
        p.left - 6.0, y, p.left, y);
    add(s, "<text class=\"ytick\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"11\" text-anchor=\"end\">{:.{}f}</text>\n",
        p.left - 9.0, y + 4.0, v, decimals);
  }
  add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\" text-anchor=\"middle\">{}</text>\n",
      p.left + kPlotWidth / 2.0, bottom + 40.0, x_title);
  const double ty_x = p.left - 52.0, ty_y = kPlotTop + kPlotHeight / 2.0;
  add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\" text-anchor=\"middle\" "
         "transform=\"rotate(-90 {:.2f} {:.2f})\">{}</text>\n", ty_x, ty_y, ty_x, ty_y, y_title);
}

}  // namespace

std::string pareto_svg(const std::vector<PlotPoint>& points, const std::string& title,
                       const std::string& score_name) {
  // Series in order of first appearance, so colours do not depend on names.
  std::vector<std::string> series;
  std::vector<int> series_of(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    auto it = std::find(series.begin(), series.end(), points[i].series);
    series_of[i] = int(it - series.begin());
    if (it == series.end()) series.push_back(points[i].series);
  }
  std::vector<double> times, megabytes;
  bool any_bytes = false;
  for (const PlotPoint& p : points) {
    times.push_back(p.time_ms);
    any_bytes = any_bytes || p.bytes > 0.0;
    megabytes.push_back(p.bytes > 0.0 ? p.bytes * 1e-6 : std::nan(""));
  }
  int decade_lo = 0, decade_hi = 1, mb_lo = 0, mb_hi = 1;
  time_decades(times, decade_lo, decade_hi);
  time_decades(megabytes, mb_lo, mb_hi);
  const int panels = any_bytes ? 3 : 2;
  const double width = 80.0 + double(panels) * kPanelStep - 50.0;  // 960 px for two panels

  std::string s;
  add(s, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" "
         "viewBox=\"0 0 {:.0f} {:.0f}\" font-family=\"sans-serif\">\n", width, kHeight, width, kHeight);
  add(s, "<rect width=\"{:.0f}\" height=\"{:.0f}\" fill=\"#fff\"/>\n", width, kHeight);
  add(s, "<text x=\"{:.2f}\" y=\"26\" font-size=\"16\" text-anchor=\"middle\">{}</text>\n",
      width / 2.0, escape_xml(title).c_str());

  // Legend: one entry per series, then the front's line and ring.
  double lx = kPlotLeft[0];
  const double ly = 52.0;
  for (size_t k = 0; k < series.size(); ++k) {
    marker(s, "legend", shape_of(int(k)), lx, ly, kPalette[k % kPaletteSize]);
    add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">{}</text>\n", lx + 10.0, ly + 4.0,
        escape_xml(series[k]).c_str());
    lx += 34.0 + 7.0 * double(series[k].size());
  }
  add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\" "
         "stroke-width=\"1.2\" stroke-dasharray=\"4 3\"/>\n", lx - 6.0, ly, lx + 18.0, ly);
  add(s, "<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"none\" stroke=\"#333\"/>\n", lx + 6.0,
      ly, kRingRadius);
  add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">Pareto front</text>\n", lx + 24.0, ly + 4.0);
  const bool any_chosen = std::any_of(points.begin(), points.end(), [](const PlotPoint& p) { return p.chosen; });
  if (any_chosen) {
    lx += 112.0;
    add(s, "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" "
           "stroke=\"#d00\" stroke-width=\"1.5\"/>\n", lx, ly - kRingRadius, 2.0 * kRingRadius, 2.0 * kRingRadius);
    add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">best for a budget</text>\n", lx + 18.0, ly + 4.0);
  }

  for (int panel = 0; panel < panels; ++panel) {
    Panel p;
    p.left = kPlotLeft[panel];
    p.decade_lo = panel == 2 ? mb_lo : decade_lo;
    p.decade_hi = panel == 2 ? mb_hi : decade_hi;
    // A point is in this panel only with a finite cost and y; the rest get NaN (never on the front).
    std::vector<double> cost(points.size()), score(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const double y = panel == 1 ? points[i].fidelity : points[i].total;
      const double x = panel == 2 ? megabytes[i] : points[i].time_ms;
      const bool ok = std::isfinite(x) && std::isfinite(y);
      cost[i] = ok ? x : std::nan("");
      score[i] = ok ? y : std::nan("");
    }
    score_range(score, p.y_lo, p.y_hi);
    draw_axes(s, p, panel == 1 ? "fidelity" : score_name.c_str(),
              panel == 2 ? "map bytes touched (MB, log scale)" : "shadow time (ms, log scale)");

    // Front as a staircase in time order: best score reachable within a time budget.
    const std::vector<bool> front = pareto_front(cost, score);
    std::vector<size_t> order;
    for (size_t i = 0; i < points.size(); ++i)
      if (front[i]) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      if (cost[a] != cost[b]) return cost[a] < cost[b];
      if (score[a] != score[b]) return score[a] > score[b];
      return a < b;
    });
    if (!order.empty()) {
      s += "<polyline class=\"front\" fill=\"none\" stroke=\"#333\" stroke-width=\"1.2\" "
           "stroke-dasharray=\"4 3\" points=\"";
      for (size_t k = 0; k < order.size(); ++k) {
        const double x = p.px(cost[order[k]]), y = p.py(score[order[k]]);
        if (k > 0) add(s, " {:.2f},{:.2f}", x, p.py(score[order[k - 1]]));
        add(s, "{}{:.2f},{:.2f}", k > 0 ? " " : "", x, y);
      }
      s += "\"/>\n";
    }
    for (size_t i = 0; i < points.size(); ++i) {
      if (std::isnan(cost[i])) continue;
      const int k = series_of[i];
      marker(s, "pt", shape_of(k), p.px(cost[i]), p.py(score[i]),
             kPalette[k % kPaletteSize]);
    }
    for (size_t i : order)
      add(s, "<circle class=\"ring\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"none\" "
             "stroke=\"#333\" stroke-width=\"1.2\"/>\n", p.px(cost[i]), p.py(score[i]), kRingRadius);
    for (size_t i = 0; i < points.size(); ++i)
      if (points[i].chosen && !std::isnan(cost[i]))
        add(s, "<rect class=\"chosen\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" "
               "fill=\"none\" stroke=\"#d00\" stroke-width=\"1.5\"/>\n", p.px(cost[i]) - kRingRadius,
            p.py(score[i]) - kRingRadius, 2.0 * kRingRadius, 2.0 * kRingRadius);
    for (size_t i = 0; i < points.size(); ++i) {
      if (std::isnan(cost[i])) continue;
      add(s, "<text class=\"lbl\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"9\" fill=\"#222\">{}</text>\n",
          p.px(cost[i]) + 7.0, p.py(score[i]) - 6.0, escape_xml(points[i].label).c_str());
    }
  }
  s += "</svg>\n";
  return s;
}

void write_pareto_svg(const std::string& path, const std::vector<PlotPoint>& points,
                      const std::string& title, const std::string& score_name) {
  // write_text_file's error names the path and the OS's reason.
  write_text_file(path, pareto_svg(points, title, score_name));
}

}  // namespace shadowlab
