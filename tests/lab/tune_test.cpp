// The tuner's decisions on hand-made numbers: the budget winner and halving's survivors.
#include <gtest/gtest.h>

#include "core/error.h"
#include "lab/tune_report.h"
#include "lab/tuner.h"

namespace shadowlab {
namespace {

TuneSummary summary(size_t point, const std::string& technique, double objective, double ms, double bytes) {
  TuneSummary s;
  s.point = point;
  s.technique = technique;
  s.spec = technique + std::to_string(point);
  s.objective = objective;
  s.time_ms = ms;
  s.bytes = bytes;
  return s;
}

TEST(Tune, EveryObjectiveReadsItsOwnField) {
  // Each field a distinct value: an objective that read another field, or fell through to the
  // next name, would return another number. flip is maximized as 1 − mean FLIP.
  MetricReport m;
  double v = 0.01;
  for (double* f : {&m.total, &m.fidelity, &m.aesthetics, &m.detail, &m.ssim, &m.psnr, &m.c10,
                    &m.c50, &m.c90, &m.dark, &m.lit, &m.acne, &m.noise, &m.flip_mean})
    *f = (v += 0.01);
  const std::vector<std::pair<std::string, double>> want{
      {"total", m.total}, {"fidelity", m.fidelity}, {"aesthetics", m.aesthetics},
      {"detail", m.detail}, {"ssim", m.ssim}, {"psnr", m.psnr}, {"c10", m.c10}, {"c50", m.c50},
      {"c90", m.c90}, {"dark", m.dark}, {"lit", m.lit}, {"acne", m.acne}, {"noise", m.noise},
      {"flip", 1.0 - m.flip_mean}};
  ASSERT_EQ(want.size(), tune_objectives().size());
  for (const auto& [name, value] : want) EXPECT_EQ(objective_value(m, name), value) << name;
  EXPECT_THROW(objective_value(m, "speed"), InputError);
}

// A tune.json records the config; merge reads it back with the same ranges as tune's flags
// (--max-evals up to 1e8, --spp up to 2^20, --repeats up to 100000): a config at each flag's
// upper end is read back as written, and one past it is refused.
TEST(Tune, ConfigsAtTheFlagsUpperEndsReadBack) {
  TuneConfig c;
  c.max_evals = 100000000;
  c.spp = 1 << 20;
  c.repeats = 100000;
  const TuneConfig back = tune_config_from_json(tune_config_json(c), "tune.json");
  EXPECT_EQ(back.max_evals, c.max_evals);
  EXPECT_EQ(back.spp, c.spp);
  EXPECT_EQ(back.repeats, c.repeats);
  for (const char* key : {"max_evals", "spp", "repeats"}) {
    nlohmann::json j = tune_config_json(c);
    j[key] = j[key].get<uint64_t>() + 1;
    EXPECT_THROW(tune_config_from_json(j, "tune.json"), InputError) << key;
  }
}

TEST(Tune, BudgetWinnerIsTheBestThatFitsThenTheCheapest) {
  const std::vector<TuneSummary> s = {
      summary(0, "csm", 0.80, 1.0, 100), summary(1, "csm", 0.90, 3.0, 400),
      summary(2, "cvsm", 0.90, 2.0, 900), summary(3, "cvsm", 0.95, 8.0, 50),
      summary(4, "csm", 0.90, 2.0, 300)};
  EXPECT_EQ(best_under(s, 0.5, false), nullptr);           // nothing fits
  EXPECT_EQ(best_under(s, 1.0, false)->point, 0u);         // a cost equal to the budget fits
  EXPECT_EQ(best_under(s, 2.5, false)->point, 2u);         // 0.90 at 2 ms twice: lower index
  EXPECT_EQ(best_under(s, 3.0, false)->point, 2u);         // 0.90 at 3 ms loses to 2 ms
  EXPECT_EQ(best_under(s, 10.0, false)->point, 3u);
  EXPECT_EQ(best_under(s, 2.5, false, "csm")->point, 4u);  // per technique
  EXPECT_EQ(best_under(s, 60.0, true)->point, 3u);         // bytes budget
  EXPECT_EQ(best_under(s, 350.0, true, "csm")->point, 4u);
}

// The plot marks the budgets' winners and nothing else: three points on one scene at 1, 2 and
// 4 ms with objectives 0.6, 0.8, 0.9; budgets of 2.5 and 10 ms choose the second and third.
TEST(Tune, PlotMarksExactlyTheBudgetWinners) {
  TuneResult r;
  r.scenes = {"default"};
  const double ms[] = {1.0, 2.0, 4.0}, objective[] = {0.6, 0.8, 0.9};
  for (size_t k = 0; k < 3; ++k) {
    TuneEval e;
    e.index = k;
    e.point = k;
    e.technique = "csm";
    e.spec = "csm:res=" + std::to_string(256 << k);
    e.lookup_ms = ms[k];
    e.objective = objective[k];
    r.points.push_back(e.spec);
    r.evals.push_back(e);
  }
  r.rung_total[1] = 3;
  TuneConfig c;
  c.budgets_ms = {2.5, 10.0};
  const std::vector<PlotPoint> p = tune_plot_points(r, c);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_FALSE(p[0].chosen);
  EXPECT_TRUE(p[1].chosen);
  EXPECT_TRUE(p[2].chosen);
  c.budgets_ms = {0.5};
  for (const PlotPoint& q : tune_plot_points(r, c)) EXPECT_FALSE(q.chosen) << q.label;
}

TEST(Tune, HalvingKeepsNonDominatedLayersUntilAThird) {
  // Nine points. Layer 1 (no point has fewer bytes and a higher objective): 0, 3, 6.
  // Layer 2 after removing them: 1, 4, 7. eta = 3 needs 3 points: layer 1 only.
  const std::vector<double> obj = {0.5, 0.4, 0.1, 0.7, 0.6, 0.2, 0.9, 0.8, 0.3};
  const std::vector<double> bytes = {1, 1.5, 2, 2, 2.5, 3, 3, 3.5, 4};
  EXPECT_EQ(halving_survivors(obj, bytes, 3), (std::vector<size_t>{0, 3, 6}));
  // eta = 2 needs 5: layers 1 and 2 (6 points).
  EXPECT_EQ(halving_survivors(obj, bytes, 2), (std::vector<size_t>{0, 1, 3, 4, 6, 7}));
  // eta = 1 keeps everything.
  EXPECT_EQ(halving_survivors(obj, bytes, 1).size(), 9u);
  // Ties do not dominate each other: both stay.
  EXPECT_EQ(halving_survivors({0.5, 0.5, 0.1}, {1, 1, 1}, 3), (std::vector<size_t>{0, 1}));
}

}  // namespace
}  // namespace shadowlab
