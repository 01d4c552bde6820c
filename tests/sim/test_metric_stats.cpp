// Statistics authors need (aggregate.csv's median, quantiles, standard error and Student t
// confidence interval) and the metric metadata kinds declare (labels, units, direction,
// headline, result or setting) as the sweep tables use them.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/metrics.hpp"
#include "sim/study/metric_stats.hpp"
#include "sim/study/sweep_store.hpp"
#include "sim/study/sweep_tables.hpp"
#include "test_kind.hpp"

namespace formsim::sim {
namespace {

TEST(MetricStats, QuantilesStandardErrorAndStudentInterval) {
  const MetricStats s = StatsOf({4, 1, 3, 2});
  EXPECT_EQ(s.n, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  // Type 7: h = p (n - 1); q05 = 1 + 0.15 (2 - 1), q95 = 3 + 0.85 (4 - 3).
  EXPECT_DOUBLE_EQ(s.q05, 1.15);
  EXPECT_DOUBLE_EQ(s.q95, 3.85);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.sem, s.std / 2.0);
  // t(0.975, 3) = 3.182446 (qt in R): half-width 3.182446 · sqrt(5/3) / 2 = 2.054260.
  EXPECT_NEAR(s.ci95_half(), 2.054260, 1e-6);
  EXPECT_NEAR(s.ci95_lo, 2.5 - 2.054260, 1e-6);
  EXPECT_NEAR(s.ci95_hi, 2.5 + 2.054260, 1e-6);
  // Odd count: the median is the middle value; one value: no spread, no interval.
  EXPECT_EQ(StatsOf({5, 1, 9}).median, 5.0);
  const MetricStats one = StatsOf({7});
  EXPECT_EQ(one.median, 7.0);
  EXPECT_EQ(one.q05, 7.0);
  EXPECT_TRUE(std::isnan(one.std) && std::isnan(one.sem) && std::isnan(one.ci95_lo));
  const MetricStats none = StatsOf({});
  EXPECT_EQ(none.n, 0u);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.median) && std::isnan(none.ci95_hi));
  // Zero spread: the interval closes on the mean.
  const MetricStats same = StatsOf({2, 2, 2});
  EXPECT_EQ(same.ci95_lo, 2.0);
  EXPECT_EQ(same.ci95_hi, 2.0);
}

TEST(MetricStats, StudentTMatchesR) {
  // R: qt(0.975, df) for the table's ends and beyond it (the expansion).
  const std::pair<std::size_t, double> want[] = {
      {1, 12.706205}, {2, 4.302653},  {3, 3.182446},  {9, 2.262157},   {30, 2.042272},
      {31, 2.039513}, {40, 2.021075}, {60, 2.000298}, {120, 1.979930}, {1000, 1.962339}};
  for (const auto& [dof, t] : want) EXPECT_NEAR(StudentT975(dof), t, 1e-6) << dof;
  EXPECT_THROW(StudentT975(0), std::invalid_argument);
  // Monotone decreasing towards the normal quantile.
  for (std::size_t v = 1; v < 400; ++v) EXPECT_GT(StudentT975(v), StudentT975(v + 1)) << v;
  EXPECT_GT(StudentT975(100000), 1.959963);
}

// A run's results as a kind declares them: two links' errors, a setting, labels and a headline.
Metrics KindResults(double e12, double e23, double period) {
  Metrics m;
  m.SetSetting("control_period", period);
  m.Set("links.R1-R2.max_abs_error.l", 10 * e12);
  m.Set("links.R1-R2.max_abs_error_after_settle.l", e12);
  m.Set("links.R2-R3.max_abs_error_after_settle.l", e23);
  m.SetText("links.R1-R2.law", "l-phi");
  m.Describe("control_period", "control period", "s");
  m.Describe("links.*.max_abs_error.l", "max|e_{l}| over the run, link {1}", "m");
  m.Describe("links.*.max_abs_error_after_settle.*", "max|e_{{2}}| after settling, link {1}", "m",
             Better::kLower);
  m.AddHeadline(
      {"max|e_l| [m]", "links.*.max_abs_error_after_settle.l", Metrics::Combine::kMax, "%.3g"});
  return m;
}

TEST(MetricInfo, LabelsUnitsDirectionHeadlineAndRole) {
  const Metrics m = KindResults(0.1, 0.2, 0.05);
  std::vector<std::string> caps;
  ASSERT_TRUE(PathCaptures("links.*.max_abs_error_after_settle.*",
                           "links.R1-R2.max_abs_error_after_settle.l", &caps));
  EXPECT_EQ(caps, (std::vector<std::string>{"R1-R2", "l"}));
  EXPECT_FALSE(PathCaptures("links.*.rmse", "links.R1-R2.max", &caps));
  const MetricInfo a = m.InfoOf("links.R2-R3.max_abs_error_after_settle.l");
  EXPECT_EQ(a.label, "max|e_{l}| after settling, link R2-R3");
  EXPECT_EQ(a.unit, "m");
  EXPECT_EQ(a.AxisLabel("x"), "max|e_{l}| after settling, link R2-R3 [m]");
  EXPECT_EQ(a.better, Better::kLower);
  EXPECT_EQ(a.headline, 1);
  EXPECT_EQ(a.role, MetricRole::kResult);
  const MetricInfo w = m.InfoOf("links.R1-R2.max_abs_error.l");
  EXPECT_EQ(w.headline, 0);
  EXPECT_EQ(w.better, Better::kNone);
  const MetricInfo p = m.InfoOf("control_period");
  EXPECT_EQ(p.role, MetricRole::kSetting);
  EXPECT_EQ(p.AxisLabel("control_period"), "control period [s]");
  EXPECT_EQ(m.InfoOf("undeclared.path").AxisLabel("undeclared.path"), "undeclared.path");
  // Settings stay in summary.json (Scalars) but apart from the results.
  EXPECT_EQ(m.Scalars().size(), 4u);
  ASSERT_EQ(m.Scalars(MetricRole::kSetting).size(), 1u);
  EXPECT_EQ(m.Scalars(MetricRole::kSetting)[0].first, "control_period");
  EXPECT_EQ(m.Scalars(MetricRole::kResult).size(), 3u);
  // Without declared headlines the first three numbers stand in, never a setting.
  Metrics plain;
  plain.SetSetting("period", 1);
  plain.Set("x", 2);
  ASSERT_EQ(plain.Headlines().size(), 1u);
  EXPECT_EQ(plain.Headlines()[0].label, "x");
}

SweepDefinition TwoPoints() {
  return DefineSweep(ScenarioSource::FromText(testkind::kScenario, "circle.yaml", ""), {},
                     {"v=0.5,1"}, {1, 2});
}

TEST(SweepTables, SettingsLeaveTheMetricsAndTheFirstHeadlineIsTheDefault) {
  const SweepDefinition d = TwoPoints();
  std::vector<SweepRecord> recs;
  for (std::size_t r = 0; r < d.runs(); ++r) {
    SweepRecord rec;
    rec.run = r;
    rec.status = "completed";
    // The whole-run maximum varies the most, but the headline is the after-settling error.
    FillRecordMetrics(KindResults(0.1 + 0.01 * r, 0.3, 0.05), &rec);
    // Through the record files: the settings and descriptions survive, byte for byte.
    const SweepRecord back = ParseRecord(RecordText(d, rec), d, "r");
    EXPECT_EQ(RecordText(d, back), RecordText(d, rec));
    recs.push_back(back);
  }
  ASSERT_EQ(recs[0].settings.size(), 1u);
  ASSERT_EQ(recs[0].info.size(), 3u);
  const SweepTables t = BuildSweepTables(d, recs);
  EXPECT_EQ(t.metrics, (std::vector<std::string>{"links.R1-R2.max_abs_error.l",
                                                 "links.R1-R2.max_abs_error_after_settle.l",
                                                 "links.R2-R3.max_abs_error_after_settle.l"}));
  EXPECT_EQ(t.settings, (std::vector<std::string>{"control_period"}));
  const std::string head = t.runs_csv.substr(0, t.runs_csv.find('\n'));
  EXPECT_EQ(head,
            "run,v,seed,links.R1-R2.max_abs_error.l,links.R1-R2.max_abs_error_after_settle.l,"
            "links.R2-R3.max_abs_error_after_settle.l,settings.control_period,status,message");
  EXPECT_NE(t.runs_csv.find("\n0,0.5,1,1,0.1,0.3,0.05,completed,\n"), std::string::npos)
      << t.runs_csv;
  // aggregate.csv: every statistic per metric, then the settings the point's runs agree on.
  const std::string agg_head = t.aggregate_csv.substr(0, t.aggregate_csv.find('\n'));
  const std::string m = "links.R2-R3.max_abs_error_after_settle.l";
  EXPECT_NE(agg_head.find("," + m + ".n," + m + ".mean," + m + ".std," + m + ".min," + m + ".max," +
                          m + ".median," + m + ".q05," + m + ".q95," + m + ".sem," + m +
                          ".ci95_lo," + m + ".ci95_hi,settings.control_period"),
            std::string::npos)
      << agg_head;
  EXPECT_EQ(agg_head.find("control_period.mean"), std::string::npos);
  EXPECT_NE(t.aggregate_csv.find(",0.05\n"), std::string::npos) << t.aggregate_csv;
  EXPECT_EQ(DefaultMetric(t), 1u);
  EXPECT_EQ(MetricAxisLabel(t, 1), "max|e_{l}| after settling, link R1-R2 [m]");
  EXPECT_EQ(MetricAxisLabel(t, 0), "max|e_{l}| over the run, link R1-R2 [m]");
  // Point 1 (runs 2 and 3): values 0.12 and 0.13.
  const MetricStats& s = t.stats[1][1];
  EXPECT_DOUBLE_EQ(s.median, 0.125);
  EXPECT_NEAR(s.ci95_hi - s.mean, 12.706205 * s.std / std::sqrt(2.0), 1e-12);
  // Records without metadata (an older sweep): the first metric that varies.
  for (SweepRecord& r : recs) r.info.clear();
  EXPECT_EQ(DefaultMetric(BuildSweepTables(d, recs)), 0u);
}

}  // namespace
}  // namespace formsim::sim
