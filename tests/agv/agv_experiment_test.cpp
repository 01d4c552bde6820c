// The Mecanum AGV experiment end to end: the paper's comparison (seeded), gate, faults,
// determinism and scenario validation.
#include "sim/agv/agv_experiment.hpp"

#include <gtest/gtest.h>

#include "tests/support/invalid_fixtures.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "control/common/angle.hpp"

namespace formsim::sim {
namespace {

const std::string kFused = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/agv_fused.yaml";

std::unique_ptr<Experiment> RunToEnd(const std::string& file,
                                     const std::vector<std::string>& sets = {}) {
  auto exp = LoadExperiment(file, sets);
  while (!exp->finished()) exp->Step();
  return exp;
}

const AgvExperiment& Agv(const std::unique_ptr<Experiment>& e) {
  const auto* a = dynamic_cast<const AgvExperiment*>(e.get());
  EXPECT_NE(a, nullptr);
  return *a;
}

TEST(AgvExperiment, FusionTracksWithinBoundThatOdometryAloneExceeds) {
  const auto fused = RunToEnd(kFused);
  const auto odo = RunToEnd(kFused, {"localisation.mode=odometry"});
  const AgvExperiment& f = Agv(fused);
  const AgvExperiment& o = Agv(odo);
  const double bound = 0.015;  // m
  EXPECT_TRUE(f.completed());
  EXPECT_LT(f.cross_track().max_abs, bound);
  EXPECT_LT(f.cross_track().rms(), 0.006);
  EXPECT_GT(o.cross_track().max_abs, 10 * bound);
  EXPECT_FALSE(o.completed());
  // Odometry drifts, the fused estimate does not.
  EXPECT_GT(o.odometry_stats().position.max_abs, 0.2);
  EXPECT_LT(f.fused_stats().position.max_abs, 0.03);
}

TEST(AgvExperiment, BeaconAloneJumpsAndFusedEstimateDoesNot) {
  const auto b = RunToEnd(kFused, {"localisation.mode=beacon"});
  const AgvExperiment& a = Agv(b);
  EXPECT_TRUE(a.completed());
  EXPECT_GT(a.beacon_stats().jumps, 20);
  EXPECT_GT(a.beacon_stats().position.max_abs, 0.2);
  EXPECT_EQ(a.fused_stats().jumps, 0);
  // The robot driven by the raw beacon is worse than the fused one.
  const auto f = RunToEnd(kFused);
  EXPECT_GT(a.cross_track().max_abs, Agv(f).cross_track().max_abs);
}

TEST(AgvExperiment, GateRejectsTheInterferenceOutliers) {
  const auto on = RunToEnd(kFused);
  const BeaconCounts& c = Agv(on).beacon_counts();
  ASSERT_GT(c.outliers, 10);
  EXPECT_EQ(c.accepted_outliers, 0);
  EXPECT_EQ(c.rejected_outliers, c.outliers);
  EXPECT_LE(c.rejected - c.rejected_outliers, 2);  // good samples rejected
  // The paper's plain filter (no gate) lets them in and the estimate jumps.
  const auto off = RunToEnd(kFused, {"estimation.gate=false"});
  EXPECT_EQ(Agv(off).beacon_counts().rejected, 0);
  EXPECT_GT(Agv(off).fused_stats().jumps, 5);
  EXPECT_GT(Agv(off).cross_track().max_abs, 2 * Agv(on).cross_track().max_abs);
}

TEST(AgvExperiment, HeadingWrapsAcrossPiOnTheTopSide) {
  // The loop is driven with a tangent heading: θ passes ±π on the top side. The fused heading
  // error must stay small there (a wrap bug would show as a 2π error or a spin).
  const auto e = RunToEnd(kFused);
  const Recorder& r = e->recorder();
  const int th = r.Column("theta"), herr = r.Column("herr_fused");
  bool near_pi = false;
  for (std::size_t i = 0; i < r.rows(); ++i) {
    if (std::abs(r.At(i, th)) > control::kPi - 0.02) near_pi = true;
    EXPECT_LT(std::abs(r.At(i, herr)), 2.0) << "row " << i;  // degrees
  }
  EXPECT_TRUE(near_pi);
  EXPECT_LT(Agv(e).fused_stats().heading.max_abs, 0.03);
}

TEST(AgvExperiment, SameSeedIsBitIdenticalAndSeedMatters) {
  const auto a = RunToEnd(kFused), b = RunToEnd(kFused);
  const Recorder &ra = a->recorder(), &rb = b->recorder();
  ASSERT_EQ(ra.rows(), rb.rows());
  ASSERT_EQ(ra.columns(), rb.columns());
  bool all_equal = true;
  for (std::size_t i = 0; i < ra.rows(); ++i)
    for (int c = 0; c < static_cast<int>(ra.columns()); ++c) {
      const double x = ra.At(i, c), y = rb.At(i, c);
      if (!(x == y || (std::isnan(x) && std::isnan(y)))) all_equal = false;
    }
  EXPECT_TRUE(all_equal);
  auto c = LoadExperiment(kFused, {}, 99);
  while (!c->finished()) c->Step();
  EXPECT_NE(c->recorder().At(c->recorder().rows() - 1, c->recorder().Column("fused_x")),
            ra.At(ra.rows() - 1, ra.Column("fused_x")));
}

TEST(AgvExperiment, FilterFaultIsAnEventNotANaN) {
  // Q = R = 0: after the first update P = 0 and S = P + R is singular at the next sample.
  const auto e = RunToEnd(kFused, {"estimation.q_xy=0", "estimation.q_theta=0", "estimation.r_xy=0",
                                   "estimation.r_theta=0", "estimation.gate=false", "duration=5"});
  bool fault = false;
  for (const Event& ev : e->events())
    if (ev.kind == "filter_fault") {
      fault = true;
      EXPECT_EQ(ev.robots, "AGV");
      EXPECT_GT(ev.time, 0.0);
    }
  EXPECT_TRUE(fault);
  const Recorder& r = e->recorder();
  for (const char* col : {"fused_x", "fused_y", "fused_theta", "fused_sd_x"})
    for (std::size_t i = 0; i < r.rows(); ++i) EXPECT_TRUE(std::isfinite(r.At(i, r.Column(col))));
  EXPECT_GT(Agv(e).beacon_counts().faults, 0);
}

TEST(AgvExperiment, LiveModeSwitchChangesTheControlSource) {
  auto exp = LoadExperiment(kFused, {"localisation.mode=odometry"});
  for (int k = 0; k < 300 * 30; ++k) exp->Step();  // 30 s on odometry: drifting
  const double odo_err = Agv(exp).odometry_stats().final_position_error;
  EXPECT_GT(odo_err, 0.05);
  PendingChanges ch;
  ch.edits.push_back({"localisation.mode", "fused"});
  EXPECT_TRUE(exp->Apply(ch).empty());
  EXPECT_EQ(Agv(exp).config().mode, LocalisationMode::kFused);
  while (!exp->finished()) exp->Step();
  // Back on the path at the end.
  EXPECT_LT(std::abs(exp->recorder().At(exp->recorder().rows() - 1,
                                        exp->recorder().Column("cross_track"))),
            0.02);
}

TEST(AgvExperiment, ShippedScenariosLoadAndFinish) {
  const std::string dir = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios";
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string stem = entry.path().filename().string();
    if (stem.rfind("agv_", 0) != 0) continue;
    const auto e = RunToEnd(entry.path().string());
    EXPECT_TRUE(Agv(e).tracker().finished()) << stem;
    EXPECT_FALSE(e->Figures().empty());
    EXPECT_NE(e->SummaryTable().find("cross-track"), std::string::npos);
    ++n;
  }
  EXPECT_GE(n, 3);
}

// Every tests/fixtures/invalid/agv_*.yaml starts with "# expect: <text>"; loading it must throw
// a ScenarioError that contains the text and points at a line holding the offending key.
TEST(AgvExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  const int checked = formsim::testing::CheckInvalidFixtures("agv_");
  EXPECT_GE(checked, 8);
}

}  // namespace
}  // namespace formsim::sim
