// The inspection experiment end to end: the U-route run, determinism, live params, outputs and
// the invalid scenario fixtures.
#include <gtest/gtest.h>

#include "tests/support/invalid_fixtures.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sim/inspection/inspection_experiment.hpp"

namespace formsim::sim {
namespace {

const std::string kDir = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/";
const std::string kRoute = kDir + "inspection_u_route.yaml";

InspectionExperiment& AsInspection(std::unique_ptr<Experiment>& e) {
  auto* p = dynamic_cast<InspectionExperiment*>(e.get());
  EXPECT_NE(p, nullptr);
  return *p;
}

void RunToEnd(Experiment& e) {
  while (!e.finished()) e.Step();
}

bool HasEvent(const Experiment& e, const std::string& kind) {
  for (const auto& ev : e.events())
    if (ev.kind == kind) return true;
  return false;
}

// The acceptance run: the robot starts 0.4 m off the centre line, converges, drives the
// whole U and stays within the lateral bound; the Kalman estimate beats the raw fixes.
TEST(InspectionExperiment, CompletesTheURouteWithinTheLateralBound) {
  auto e = LoadExperiment(kRoute);
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_TRUE(x.completed());
  EXPECT_LT(x.completion_time(), e->setup().duration);
  ASSERT_GT(x.lateral_tracking().n, 1000);
  EXPECT_LT(x.lateral_tracking().max_abs, x.config().lateral_bound);
  EXPECT_LT(x.lateral_tracking().max_abs, 0.1);
  EXPECT_LT(x.lateral_tracking().rms(), 0.03);
  EXPECT_GT(x.fixes(), 0.95 * x.scans());
  EXPECT_LT(x.error_kalman().rms(), 0.05);
  EXPECT_LT(x.error_kalman().rms(), x.error_raw().rms());
  EXPECT_LT(x.error_kalman().max_abs, x.error_raw().max_abs);
  EXPECT_GT(x.error_dead_reckoning().max_abs, 0.5);  // what the laser fixes are there for
  EXPECT_NEAR(static_cast<double>(x.control_updates()) / e->time(), 5.0, 0.05);
  EXPECT_FALSE(HasEvent(*e, "filter_fault"));
  EXPECT_FALSE(HasEvent(*e, "fuzzy_no_rule"));
  const Json s = e->Summary();
  ASSERT_NE(s.Get("tracking"), nullptr);
  EXPECT_NE(e->SummaryTable().find("per-axis Kalman"), std::string::npos);
}

TEST(InspectionExperiment, WithoutKalmanTheClassicalChainDrives) {
  auto e = LoadExperiment(kDir + "inspection_no_kalman.yaml");
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_TRUE(x.completed());
  EXPECT_LT(x.lateral_tracking().max_abs, x.config().lateral_bound);
  // The classical filter smooths the raw fixes, the Kalman filter (running alongside) more.
  EXPECT_LT(x.error_classical().rms(), x.error_raw().rms());
  EXPECT_LT(x.error_kalman().rms(), x.error_classical().rms());
}

std::vector<double> AllValues(const Recorder& r) {
  std::vector<double> v;
  for (std::size_t i = 0; i < r.rows(); ++i)
    for (std::size_t c = 0; c < r.columns(); ++c) v.push_back(r.At(i, static_cast<int>(c)));
  return v;
}

bool BitIdentical(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

TEST(InspectionExperiment, SameSeedSameRunOtherSeedOtherNoise) {
  const std::vector<std::string> short_run = {"duration=4"};
  auto a = LoadExperiment(kRoute, short_run), b = LoadExperiment(kRoute, short_run);
  auto c = LoadExperiment(kRoute, short_run, 99);
  RunToEnd(*a);
  RunToEnd(*b);
  RunToEnd(*c);
  EXPECT_TRUE(BitIdentical(AllValues(a->recorder()), AllValues(b->recorder())));
  EXPECT_FALSE(BitIdentical(AllValues(a->recorder()), AllValues(c->recorder())));
  EXPECT_EQ(a->recorder().names().front(), "t");
}

TEST(InspectionExperiment, WithoutPostsInRangeThereIsNoFixAndNoNaN) {
  auto e = LoadExperiment(kRoute, {"duration=3", "localisation.max_range=0.5"});
  auto& x = AsInspection(e);
  RunToEnd(*e);
  EXPECT_EQ(x.fixes(), 0);
  EXPECT_GT(x.scans(), 100);
  const auto nav = x.NavPose();
  EXPECT_TRUE(std::isfinite(nav.x) && std::isfinite(nav.y) && std::isfinite(nav.theta));
  // The robot still drives, on dead reckoning.
  EXPECT_GT(x.TruePose().y, x.config().route_start.y + 0.5);
}

TEST(InspectionExperiment, EveryParamIsAValidScenarioPath) {
  auto e = LoadExperiment(kRoute);
  YAML::Node root = LoadYamlFile(kRoute);
  for (const Param& p : e->params().all()) {
    const std::string err = SetAtPath(root, p.key, YAML::Load(ParamTable::ToString(p)));
    EXPECT_TRUE(err.empty()) << p.key << ": " << err;
  }
  EXPECT_NO_THROW(LoadExperimentFromNode(root, kRoute));
}

TEST(InspectionExperiment, FuzzyReloadParamReloadsOrKeepsTheOldRules) {
  // A private copy of the rule base, so the test can break it.
  const std::string fll =
      (std::filesystem::temp_directory_path() / "formsim_inspection_test.fll").string();
  std::filesystem::copy_file(std::string(FORMSIM_SOURCE_DIR) + "/assets/fuzzy/inspection.fll", fll,
                             std::filesystem::copy_options::overwrite_existing);
  YAML::Node root = LoadYamlFile(kRoute);
  root["fuzzy"]["file"] = fll;
  root["duration"] = 2.0;
  auto e = LoadExperimentFromNode(root, kRoute);
  auto& x = AsInspection(e);
  PendingChanges reload;
  reload.edits.push_back({"fuzzy.reload", "true"});
  EXPECT_TRUE(e->Apply(reload).empty());
  EXPECT_TRUE(HasEvent(*e, "fuzzy_reloaded"));
  EXPECT_EQ(ParamTable::ToString(*e->params().Find("fuzzy.reload")), "false");
  // Break the file: the reload fails, is reported, and the 45 rules stay.
  {
    std::ofstream out(fll);
    out << "Engine: broken\nInputVariable: s\n";
  }
  EXPECT_TRUE(e->Apply(reload).empty());
  EXPECT_TRUE(HasEvent(*e, "fuzzy_reload_failed"));
  EXPECT_EQ(x.fuzzy().rules().size(), 45u);
  RunToEnd(*e);
  EXPECT_GT(x.control_updates(), 5);
  std::filesystem::remove(fll);
}

// Counts what the scene draws.
class CountingSink : public DrawSink {
 public:
  void Polygon(const std::vector<Vec2>&, Color, Color) override { ++shapes; }
  void Circle(Vec2, double, Color, Color) override { ++shapes; }
  void Segment(Vec2, Vec2, Color, float) override { ++segments; }
  void Polyline(const std::vector<Vec2>&, Color, float, bool) override { ++shapes; }
  void CovarianceEllipse(Vec2, double, double, double, double, Color) override { ++ellipses; }
  void Cross(Vec2, double, Color) override { ++shapes; }
  void Text(Vec2, const std::string&, Color, float, float) override { ++texts; }
  void Flash(Vec2, double, Color, float) override {}
  int shapes = 0, segments = 0, ellipses = 0, texts = 0;
};

TEST(InspectionExperiment, DrawsRaysFiguresAndTheRuleTable) {
  auto e = LoadExperiment(kRoute, {"duration=1"});
  RunToEnd(*e);
  CountingSink sink;
  e->Draw(sink);
  EXPECT_GT(sink.segments, 50);  // laser rays
  EXPECT_EQ(sink.ellipses, 1);   // Kalman covariance
  EXPECT_GE(sink.texts, 2);      // robot name and the two posts used for the fix
  int membership = 0;
  for (const FigureSpec& f : e->Figures()) {
    EXPECT_FALSE(f.series.empty()) << f.id;
    for (const SeriesSpec& s : f.series) {
      if (s.column.empty()) {
        EXPECT_EQ(s.x.size(), s.y.size()) << f.id;
      } else {
        EXPECT_GE(e->recorder().Column(s.column), 0) << f.id << ": " << s.column;
      }
      if (!s.x_column.empty()) {
        EXPECT_GE(e->recorder().Column(s.x_column), 0) << s.x_column;
      }
    }
    if (f.id.rfind("mf_", 0) == 0) {
      ++membership;
      EXPECT_TRUE(std::isfinite(f.marker_x)) << f.id;
    }
  }
  EXPECT_EQ(membership, 5);
  const auto tables = e->Tables();
  ASSERT_FALSE(tables.empty());
  ASSERT_EQ(tables[0].rows.size(), 45u);
  ASSERT_EQ(tables[0].row_strength.size(), 45u);
  double total = 0.0;
  for (double w : tables[0].row_strength) total += w;
  EXPECT_NEAR(total, 1.0, 1e-9);  // product t-norm on partitions of unity
  Vec2 lo, hi;
  e->Bounds(lo, hi);
  EXPECT_LT(lo.x, 2.0);
  EXPECT_GT(hi.y, 22.0);
}

// Every tests/fixtures/invalid/inspection_*.yaml starts with "# expect: <text>"; loading it
// must throw a ScenarioError containing the text and pointing at the offending key's line.
TEST(InspectionExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  const int checked = formsim::testing::CheckInvalidFixtures("inspection_");
  EXPECT_GE(checked, 9);
}

}  // namespace
}  // namespace formsim::sim
