#include "util/pareto_plot.h"

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

// Page layout, SVG px: a title line, the legend (as many lines as its entries need), then two
// or three plot areas side by side with room on their left for y tick labels and below for x
// tick labels and the axis title.
constexpr double kPanelStep = 465.0, kHeight = 450.0;
constexpr double kPlotTop = 78.0, kPlotHeight = 300.0, kPlotWidth = 370.0;
constexpr double kLegendLine = 20.0;  // px between legend lines
// Point labels: 9 px text; the box a label is given for the overlap test, px. Wider than a
// sans-serif font's mean advance (~0.55 em) so that real glyphs stay inside it.
constexpr double kLabelFont = 9.0, kLabelCharWidth = 0.62 * kLabelFont;
constexpr double kLabelAscent = 8.0, kLabelDescent = 2.5;
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
  double top = kPlotTop;      // plot area's top edge, px (below the legend)
  int decade_lo = 0;          // x axis spans 10^decade_lo .. 10^decade_hi ms
  int decade_hi = 1;
  double y_lo = 0.0, y_hi = 1.0;  // score range shown (padded)
  double px(double time_ms) const {
    const double t = std::log10(std::max(time_ms, kPlotMinTimeMs));
    return left + (t - decade_lo) / double(decade_hi - decade_lo) * kPlotWidth;
  }
  double py(double v) const { return top + (y_hi - v) / (y_hi - y_lo) * kPlotHeight; }
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
  const double bottom = p.top + kPlotHeight, right = p.left + kPlotWidth;
  add(s, "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"#fafafa\" "
         "stroke=\"#333\" stroke-width=\"1\"/>\n", p.left, p.top, kPlotWidth, kPlotHeight);
  // x: a labelled grid line per decade, short unlabelled ticks at 2..9 × 10^d.
  for (int d = p.decade_lo; d <= p.decade_hi; ++d) {
    const double x = p.px(std::pow(10.0, d));
    add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#ddd\"/>\n", x,
        p.top, x, bottom);
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
  const double ty_x = p.left - 52.0, ty_y = p.top + kPlotHeight / 2.0;
  add(s, "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\" text-anchor=\"middle\" "
         "transform=\"rotate(-90 {:.2f} {:.2f})\">{}</text>\n", ty_x, ty_y, ty_x, ty_y, y_title);
}


// A label's box, px: x from its anchor to the text's estimated end, y from ascent to descent.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

Box label_box(double x, double y, const std::string& text) {
  return {x, y - kLabelAscent, x + kLabelCharWidth * double(text.size()), y + kLabelDescent};
}

// Where a front point's label goes: the first of eight spots beside its ring (right, then
// left; above, below, then further out) whose box stays in the plot area and overlaps no box in
// `placed` (the front's rings, the labels placed before); false when none does (the legend and
// the CSV still name the point).
bool place_label(const Panel& p, double px, double py, const std::string& text,
                 std::vector<Box>& placed, double& x, double& y) {
  const double w = kLabelCharWidth * double(text.size());
  const double dxs[2] = {kRingRadius + 1.0, -kRingRadius - 1.0 - w};
  const double dys[4] = {-6.0, 13.0, -18.0, 25.0};
  for (double dy : dys)
    for (double dx : dxs) {
      const Box b = label_box(px + dx, py + dy, text);
      if (b.x0 < p.left || b.x1 > p.left + kPlotWidth || b.y0 < p.top || b.y1 > p.top + kPlotHeight)
        continue;
      if (std::any_of(placed.begin(), placed.end(), [&](const Box& o) { return o.overlaps(b); }))
        continue;
      placed.push_back(b);
      x = px + dx;
      y = py + dy;
      return true;
    }
  return false;
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

  // Legend: one entry per series, then the front's line and ring (and the budget square),
  // wrapped onto further lines where the page's width ends; the panels move down by them.
  const bool any_chosen = std::any_of(points.begin(), points.end(), [](const PlotPoint& p) { return p.chosen; });
  std::vector<double> entry_width;
  for (const std::string& name : series) entry_width.push_back(34.0 + 7.0 * double(name.size()));
  entry_width.push_back(112.0);             // Pareto front
  if (any_chosen) entry_width.push_back(130.0);  // best for a budget
  std::vector<double> entry_x(entry_width.size()), entry_y(entry_width.size());
  {
    double x = kPlotLeft[0], y = 52.0;
    for (size_t k = 0; k < entry_width.size(); ++k) {
      if (x > kPlotLeft[0] && x + entry_width[k] > width - 20.0) {
        x = kPlotLeft[0];
        y += kLegendLine;
      }
      entry_x[k] = x;
      entry_y[k] = y;
      x += entry_width[k];
    }
  }
  const double shift = entry_y.back() - 52.0;  // extra legend lines
  const double height = kHeight + shift;

  std::string s;
  add(s, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" "
         "viewBox=\"0 0 {:.0f} {:.0f}\" font-family=\"sans-serif\">\n", width, height, width, height);
  add(s, "<rect width=\"{:.0f}\" height=\"{:.0f}\" fill=\"#fff\"/>\n", width, height);
  add(s, "<text x=\"{:.2f}\" y=\"26\" font-size=\"16\" text-anchor=\"middle\">{}</text>\n",
      width / 2.0, escape_xml(title).c_str());

  for (size_t k = 0; k < series.size(); ++k) {
    const double lx = entry_x[k], ly = entry_y[k];
    marker(s, "legend", shape_of(int(k)), lx, ly, kPalette[k % kPaletteSize]);
    add(s, "<text class=\"legendtext\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">{}</text>\n", lx + 10.0,
        ly + 4.0, escape_xml(series[k]).c_str());
  }
  double lx = entry_x[series.size()] + 6.0;
  double ly = entry_y[series.size()];
  add(s, "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#333\" "
         "stroke-width=\"1.2\" stroke-dasharray=\"4 3\"/>\n", lx - 6.0, ly, lx + 18.0, ly);
  add(s, "<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"none\" stroke=\"#333\"/>\n", lx + 6.0,
      ly, kRingRadius);
  add(s, "<text class=\"legendtext\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">Pareto front</text>\n", lx + 24.0, ly + 4.0);
  if (any_chosen) {
    lx = entry_x.back();
    ly = entry_y.back();
    add(s, "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" "
           "stroke=\"#d00\" stroke-width=\"1.5\"/>\n", lx, ly - kRingRadius, 2.0 * kRingRadius, 2.0 * kRingRadius);
    add(s, "<text class=\"legendtext\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"12\">best for a budget</text>\n", lx + 18.0, ly + 4.0);
  }

  for (int panel = 0; panel < panels; ++panel) {
    Panel p;
    p.left = kPlotLeft[panel];
    p.top = kPlotTop + shift;
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
    // Labels for the front's points only (the rest are told apart by the legend): at 18
    // techniques x 4 resolutions a label per point would pile into an unreadable block. Each
    // goes where it overlaps no other; one that fits nowhere is left out.
    // The front's rings are in the way too: a label over a ring hides which point it marks.
    std::vector<Box> placed;
    for (size_t i : order)
      placed.push_back({p.px(cost[i]) - kRingRadius, p.py(score[i]) - kRingRadius,
                        p.px(cost[i]) + kRingRadius, p.py(score[i]) + kRingRadius});
    for (size_t i : order) {
      double x = 0.0, y = 0.0;
      if (place_label(p, p.px(cost[i]), p.py(score[i]), points[i].label, placed, x, y))
        add(s, "<text class=\"lbl\" x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"9\" fill=\"#222\">{}</text>\n",
            x, y, escape_xml(points[i].label).c_str());
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
