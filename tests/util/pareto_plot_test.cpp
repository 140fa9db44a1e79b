// The Pareto front on hand-made sets with known fronts, and the SVG's structure: one marker per
// point per panel, labels on the fronts, escaped text, decade ticks, rings on each panel's own
// front; its geometry at 18 techniques x 4 resolutions (no overlapping labels, a legend that
// fits the page).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>

#include "core/error.h"
#include "util/pareto_plot.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + 1)) ++n;
  return n;
}

// Texts of every <text class="cls" ...>…</text> element, in document order.
std::vector<std::string> texts_of_class(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::regex re("<text class=\"" + cls + "\"[^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str());
  return out;
}

TEST(ParetoFront, EmptyAndSinglePoint) {
  EXPECT_TRUE(pareto_front({}, {}).empty());
  EXPECT_EQ(pareto_front({3.0}, {0.2}), std::vector<bool>{true});
}

TEST(ParetoFront, EveryGainCostsTimeSoAllAreOnTheFront) {
  // Strictly rising score with strictly rising cost: nothing dominates anything.
  EXPECT_EQ(pareto_front({1, 2, 3}, {0.1, 0.5, 0.9}), (std::vector<bool>{true, true, true}));
}

TEST(ParetoFront, DominatedPointsAreOff) {
  // #1 is slower and worse than #0; #3 is as good as #2 but slower.
  EXPECT_EQ(pareto_front({1, 2, 3, 4}, {0.5, 0.4, 0.9, 0.9}),
            (std::vector<bool>{true, false, true, false}));
  // Input order does not matter: the same set reversed.
  EXPECT_EQ(pareto_front({4, 3, 2, 1}, {0.9, 0.9, 0.4, 0.5}),
            (std::vector<bool>{false, true, false, true}));
}

TEST(ParetoFront, TiesInCostKeepOnlyTheBetterScore) {
  EXPECT_EQ(pareto_front({2, 2}, {0.3, 0.7}), (std::vector<bool>{false, true}));
  // Ties in score keep only the cheaper one.
  EXPECT_EQ(pareto_front({5, 2}, {0.7, 0.7}), (std::vector<bool>{false, true}));
}

TEST(ParetoFront, DuplicatesDoNotDominateEachOther) {
  EXPECT_EQ(pareto_front({1, 1, 2}, {0.5, 0.5, 0.4}), (std::vector<bool>{true, true, false}));
  EXPECT_EQ(pareto_front({1, 1, 2}, {0.5, 0.5, 0.6}), (std::vector<bool>{true, true, true}));
}

TEST(ParetoFront, NanIsNeverOnTheFrontAndDominatesNothing) {
  const double nan = std::nan("");
  EXPECT_EQ(pareto_front({1, nan, 2}, {0.5, 0.9, 0.6}), (std::vector<bool>{true, false, true}));
  EXPECT_EQ(pareto_front({nan, 1}, {1.0, 0.2}), (std::vector<bool>{false, true}));
  EXPECT_EQ(pareto_front({0.5, 1}, {nan, 0.2}), (std::vector<bool>{false, true}));
}

// Seeded property test on sets with many ties: front points do not dominate each other, and
// every point off the front is dominated by a point on it (dominance is transitive).
TEST(ParetoFront, FrontIsMutuallyNonDominatedAndCoversTheRest) {
  auto dominates = [](double ca, double sa, double cb, double sb) {
    return ca <= cb && sa >= sb && (ca < cb || sa > sb);
  };
  for (uint32_t seed = 1; seed <= 50; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> level(0, 5);  // few levels → many ties and duplicates
    const size_t n = 1 + seed % 30;
    std::vector<double> cost(n), score(n);
    for (size_t i = 0; i < n; ++i) {
      cost[i] = level(rng);
      score[i] = level(rng) * 0.1;
    }
    const std::vector<bool> front = pareto_front(cost, score);
    ASSERT_EQ(front.size(), n);
    for (size_t i = 0; i < n; ++i) {
      bool covered = front[i];
      for (size_t j = 0; j < n; ++j) {
        if (front[i] && front[j]) {
          EXPECT_FALSE(dominates(cost[j], score[j], cost[i], score[i])) << "seed " << seed;
        }
        if (!front[i] && front[j] && dominates(cost[j], score[j], cost[i], score[i])) covered = true;
      }
      EXPECT_TRUE(covered) << "seed " << seed << " point " << i;
    }
  }
}

std::vector<PlotPoint> sample_points() {
  // Total front: #0, #1, #3 (#2 is slower and worse than #1). Fidelity front: #0, #2 (#1 and #3
  // are slower and worse than #0).
  return {{"CSM 128", "csm", 1.0, 0.5, 0.9},
          {"CSM 256", "csm", 2.0, 0.7, 0.8},
          {"TSM 256", "tsm", 4.0, 0.6, 0.95},
          {"TSM 512", "tsm", 8.0, 0.8, 0.7}};
}

TEST(ParetoSvg, IsOneSvgElementWithOneMarkerPerPointAndLabelsOnTheFronts) {
  const std::vector<PlotPoint> points = sample_points();
  const std::string svg = pareto_svg(points, "sweep");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  std::string trimmed = svg;
  while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.pop_back();
  EXPECT_TRUE(trimmed.size() >= 6 && trimmed.compare(trimmed.size() - 6, 6, "</svg>") == 0);
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "<script"), 0u);
  EXPECT_EQ(count(svg, "class=\"pt\""), 2 * points.size());
  // Labels on the fronts' points only, in time order: total #0, #1, #3; fidelity #0, #2.
  EXPECT_EQ(texts_of_class(svg, "lbl"),
            (std::vector<std::string>{"CSM 128", "CSM 256", "TSM 512", "CSM 128", "TSM 256"}));
  // One legend marker per series, first-appearance order.
  EXPECT_EQ(count(svg, "class=\"legend\""), 2u);
  EXPECT_LT(svg.find(">csm</text>"), svg.find(">tsm</text>"));
  // Deterministic text.
  EXPECT_EQ(svg, pareto_svg(points, "sweep"));
}

// An element's box for the overlap checks: x, y of a <text> (its baseline's start) and the text,
// at a sans-serif font's mean advance of 0.55 em, cap height 0.72 em, descent 0.2 em.
struct TextBox {
  std::string text;
  double x0, y0, x1, y1;
};

std::vector<TextBox> text_boxes(const std::string& svg, const std::string& cls) {
  std::vector<TextBox> out;
  const std::regex re("<text class=\"" + cls + "\" x=\"([-0-9.]+)\" y=\"([-0-9.]+)\" font-size=\"([0-9.]+)\"[^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1].str()), y = std::stod((*it)[2].str()), f = std::stod((*it)[3].str());
    const std::string t = (*it)[4].str();
    out.push_back({t, x, y - 0.72 * f, x + 0.55 * f * double(t.size()), y + 0.2 * f});
  }
  return out;
}

bool overlap(const TextBox& a, const TextBox& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

// A sweep of 18 techniques x 4 resolutions (the flicker and tune default lists' size): times
// grow with the resolution, scores spread so that many points crowd each other. No two point
// labels overlap, every label names a point on its panel's front (found here by brute force),
// each panel labels some of its front, and the legend's 18 entries neither overlap nor leave
// the page.
TEST(ParetoSvg, EighteenTechniquesAtFourResolutionsStayReadable) {
  const char* names[18] = {"csm", "cvsm", "cesm", "cevsm", "cmsm", "cpcss", "tsm", "tvsm", "tesm",
                           "tevsm", "tmsm", "tpcss", "dsm", "dvsm", "desm", "devsm", "dmsm", "dpcss"};
  std::vector<PlotPoint> points;
  for (int t = 0; t < 18; ++t)
    for (int r = 0; r < 4; ++r) {
      PlotPoint p;
      p.series = names[t];
      p.label = std::string(names[t]) + " " + std::to_string(128 << r);
      p.time_ms = (1.0 + 0.15 * t) * std::pow(2.2, r);
      p.total = 0.55 + 0.08 * r + 0.01 * ((t * 7) % 11);
      p.fidelity = 0.6 + 0.07 * r - 0.008 * ((t * 5) % 9);
      p.bytes = 1e6 * (1 + t % 3) * std::pow(4.0, r);
      points.push_back(p);
    }
  const std::string svg = pareto_svg(points, "18 x 4");
  const std::vector<TextBox> labels = text_boxes(svg, "lbl");
  ASSERT_FALSE(labels.empty());
  for (size_t i = 0; i < labels.size(); ++i)
    for (size_t j = i + 1; j < labels.size(); ++j)
      EXPECT_FALSE(overlap(labels[i], labels[j])) << labels[i].text << " / " << labels[j].text;
  // The fronts by brute force over the three panels' (cost, score).
  std::set<std::string> on_front;
  for (int panel = 0; panel < 3; ++panel)
    for (const PlotPoint& a : points) {
      const double ca = panel == 2 ? a.bytes : a.time_ms, sa = panel == 1 ? a.fidelity : a.total;
      bool dominated = false;
      for (const PlotPoint& b : points) {
        const double cb = panel == 2 ? b.bytes : b.time_ms, sb = panel == 1 ? b.fidelity : b.total;
        dominated |= cb <= ca && sb >= sa && (cb < ca || sb > sa);
      }
      if (!dominated) on_front.insert(a.label);
    }
  for (const TextBox& l : labels) EXPECT_TRUE(on_front.count(l.text)) << l.text << " is not on a front";
  EXPECT_LT(labels.size(), points.size());
  // The legend: one text per series, no two overlapping, all inside the page's width.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("<svg [^>]*width=\"([0-9.]+)\"")));
  const double width = std::stod(m[1].str());
  const std::vector<TextBox> legend = text_boxes(svg, "legendtext");
  ASSERT_EQ(legend.size(), 18u + 1u);  // the series and "Pareto front"
  for (size_t i = 0; i < legend.size(); ++i) {
    EXPECT_LE(legend[i].x1, width) << legend[i].text;
    for (size_t j = i + 1; j < legend.size(); ++j)
      EXPECT_FALSE(overlap(legend[i], legend[j])) << legend[i].text << " / " << legend[j].text;
    for (const TextBox& l : labels) EXPECT_FALSE(overlap(legend[i], l)) << legend[i].text << " / " << l.text;
  }
}

TEST(ParetoSvg, EachPanelRingsItsOwnFront) {
  const std::string svg = pareto_svg(sample_points(), "t");
  // 3 on the total front (left panel) + 2 on the fidelity front (right panel).
  EXPECT_EQ(count(svg, "class=\"ring\""), 5u);
  EXPECT_EQ(count(svg, "<polyline class=\"front\""), 2u);
  // The left staircase visits 3 points: 3 corners + 2 step corners = 5 vertices.
  const size_t a = svg.find("<polyline class=\"front\"");
  const size_t b = svg.find("/>", a);
  const std::string left = svg.substr(a, b - a);
  EXPECT_EQ(count(left, ","), 5u) << left;
}

TEST(ParetoSvg, WorkCountsAddABytesPanelWithItsOwnFront) {
  // Bytes: #0 2 MB, #1 50 MB, #2 1 MB, #3 300 MB; totals 0.5, 0.7, 0.6, 0.8. #2 has fewer bytes
  // and a higher total than #0, so the bytes front is #2, #1, #3.
  std::vector<PlotPoint> points = sample_points();
  const double mb[4] = {2.0, 50.0, 1.0, 300.0};
  for (size_t i = 0; i < points.size(); ++i) points[i].bytes = mb[i] * 1e6;
  const std::string svg = pareto_svg(points, "t");
  EXPECT_EQ(count(svg, "class=\"pt\""), 3 * points.size());
  EXPECT_EQ(count(svg, "<polyline class=\"front\""), 3u);
  // 3 + 2 rings on the time panels (EachPanelRingsItsOwnFront) + 3 on the bytes panel.
  EXPECT_EQ(count(svg, "class=\"ring\""), 8u);
  EXPECT_NE(svg.find("map bytes touched (MB, log scale)"), std::string::npos);
  // Bytes ticks: 1 MB .. 1000 MB after the time panels' 1 .. 10 ms.
  const std::vector<std::string> ticks = texts_of_class(svg, "xtick");
  ASSERT_EQ(ticks.size(), 2u * 2u + 4u);
  EXPECT_EQ(std::vector<std::string>(ticks.end() - 4, ticks.end()),
            (std::vector<std::string>{"1", "10", "100", "1000"}));
  // Without counts the page keeps its two panels.
  EXPECT_EQ(pareto_svg(sample_points(), "t").find("bytes touched"), std::string::npos);
}

TEST(ParetoSvg, EscapesXmlSpecialCharacters) {
  std::vector<PlotPoint> points = {{"A<B & \"C\" 'd'>", "s&t", 3.0, 0.4, 0.6}};
  const std::string svg = pareto_svg(points, "x < y & z");
  EXPECT_NE(svg.find("A&lt;B &amp; &quot;C&quot; &apos;d&apos;&gt;"), std::string::npos);
  EXPECT_NE(svg.find("s&amp;t"), std::string::npos);
  EXPECT_NE(svg.find("x &lt; y &amp; z"), std::string::npos);
  EXPECT_EQ(svg.find("A<B"), std::string::npos);
  EXPECT_EQ(svg.find("& "), std::string::npos);  // every raw '&' became an entity
}

TEST(ParetoSvg, DecadeTicksSpanHalfAMillisecondToTwoSeconds) {
  std::vector<PlotPoint> points = {{"a", "s", 0.5, 0.2, 0.3}, {"b", "s", 2000.0, 0.9, 0.8}};
  const std::vector<std::string> ticks = texts_of_class(pareto_svg(points, "t"), "xtick");
  // 0.5 ms lies in [0.1, 1), 2000 ms in [1000, 10000]: six decade ticks per panel.
  const std::vector<std::string> one_panel = {"0.1", "1", "10", "100", "1000", "10000"};
  ASSERT_EQ(ticks.size(), 12u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(ticks[i], one_panel[i]);
    EXPECT_EQ(ticks[6 + i], one_panel[i]);
  }
}

TEST(ParetoSvg, RangeInsideOneDecadeStillGetsBothEnds) {
  std::vector<PlotPoint> points = {{"a", "s", 2.0, 0.2, 0.3}, {"b", "s", 8.0, 0.9, 0.8}};
  const std::vector<std::string> ticks = texts_of_class(pareto_svg(points, "t"), "xtick");
  EXPECT_EQ(ticks, (std::vector<std::string>{"1", "10", "1", "10"}));
}

TEST(ParetoSvg, NonPositiveTimesAreClampedToTheFloor) {
  std::vector<PlotPoint> points = {{"a", "s", 0.0, 0.2, 0.3}, {"b", "s", -5.0, 0.9, 0.8},
                                   {"c", "s", 3.0, 0.5, 0.5}};
  const std::string svg = pareto_svg(points, "t");
  const std::vector<std::string> ticks = texts_of_class(svg, "xtick");
  ASSERT_FALSE(ticks.empty());
  EXPECT_EQ(ticks.front(), "0.001");  // kPlotMinTimeMs
  EXPECT_EQ(count(svg, "class=\"pt\""), 6u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(ParetoSvg, ScoreTicksHaveTwoOrThreeDecimalsAndAreDistinct) {
  // A wide range, a narrow one and a constant one.
  for (const std::vector<PlotPoint>& points :
       {std::vector<PlotPoint>{{"a", "s", 1, 0.1, 0.2}, {"b", "s", 2, 0.95, 0.99}},
        std::vector<PlotPoint>{{"a", "s", 1, 0.901, 0.5}, {"b", "s", 2, 0.912, 0.5}}}) {
    const std::vector<std::string> ticks = texts_of_class(pareto_svg(points, "t"), "ytick");
    ASSERT_GE(ticks.size(), 4u);
    const std::regex fmt("-?[0-9]+\\.[0-9]{2,3}");
    for (const std::string& t : ticks) EXPECT_TRUE(std::regex_match(t, fmt)) << t;
    const std::set<std::string> unique(ticks.begin(), ticks.end());
    // Each panel's ticks are distinct; the two panels may share values.
    EXPECT_GE(unique.size() * 2, ticks.size());
    EXPECT_EQ(std::count(ticks.begin(), ticks.end(), "-0.00"), 0);
  }
}

TEST(ParetoSvg, NonFiniteValuesAreLeftOutOfTheirPanel) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<PlotPoint> points = {{"a", "s", 1, 0.5, std::nan("")}, {"b", "s", 2, 0.6, 0.7},
                                   {"c", "s", inf, 0.9, 0.9}};
  const std::string svg = pareto_svg(points, "t");
  // Left panel: a, b; right panel: b only.
  EXPECT_EQ(count(svg, "class=\"pt\""), 3u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(ParetoSvg, WriteReportsAnUnwritablePath) {
  const std::string bad = "/no/such/folder/plot.svg";
  try {
    write_pareto_svg(bad, sample_points(), "t");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, bad);
    EXPECT_EQ(e.reason, "cannot write: No such file or directory");  // the OS's reason
  }
  const std::string good = test::binary_path("pareto_plot_test.svg");
  write_pareto_svg(good, sample_points(), "t");
  std::ifstream f(good);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), pareto_svg(sample_points(), "t"));
}

}  // namespace
}  // namespace shadowlab
