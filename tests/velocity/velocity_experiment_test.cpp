// The velocity-control experiment end to end: every scenario runs, runs are deterministic, the
// fused estimate beats odometry when the wheels slip (seeded), the PID holds a speed step
// without steady-state error, filter faults become events, and bad scenarios are rejected.
#include "sim/velocity/velocity_experiment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace formsim::sim::vio {
namespace {

const std::string kScenarios = std::string(FORMSIM_SOURCE_DIR) + "/assets/scenarios/";

std::unique_ptr<Experiment> RunToEnd(std::unique_ptr<Experiment> exp) {
  while (!exp->finished()) exp->Step();
  return exp;
}

const VelocityExperiment& Vel(const std::unique_ptr<Experiment>& e) {
  const auto* v = dynamic_cast<const VelocityExperiment*>(e.get());
  EXPECT_NE(v, nullptr);
  return *v;
}

// A one-robot straight run on a uniform floor, from YAML text.
std::unique_ptr<Experiment> OneRobot(const std::string& extra) {
  const std::string text = R"(
type: velocity_control
seed: 3
dt: 0.005
record_every: 2
landmarks: {count: 300, area: [-4, -6, 16, 6]}
estimator: {vi_baseline: false}
)" + extra;
  return LoadExperimentFromNode(YAML::Load(text), "inline.yaml");
}

TEST(VelocityExperiment, EveryScenarioLoadsAndRuns) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenarios)) {
    const std::string stem = entry.path().filename().string();
    if (stem.rfind("velocity_", 0) != 0) continue;
    auto exp = RunToEnd(LoadExperiment(entry.path().string(), {"duration=1.5"}));
    const VelocityExperiment& v = Vel(exp);
    for (int i = 0; i < v.robot_count(); ++i) {
      EXPECT_GT(v.unit(i).updates, 3) << stem;
      EXPECT_EQ(v.unit(i).faults, 0) << stem;
    }
    EXPECT_FALSE(exp->Summary().Dump().empty());
    EXPECT_FALSE(exp->Figures().empty());
    ++n;
  }
  EXPECT_GE(n, 5);
}

TEST(VelocityExperiment, SameSeedGivesBitIdenticalRecords) {
  const std::string file = kScenarios + "velocity_linear_low.yaml";
  auto a = RunToEnd(LoadExperiment(file, {"duration=3"}));
  auto b = RunToEnd(LoadExperiment(file, {"duration=3"}));
  auto c = RunToEnd(LoadExperiment(file, {"duration=3"}, 99));
  const Recorder& ra = a->recorder();
  const Recorder& rb = b->recorder();
  ASSERT_EQ(ra.rows(), rb.rows());
  ASSERT_EQ(ra.columns(), rb.columns());
  bool differs_from_other_seed = false;
  const int col = ra.Column("R_fused.v_fused");
  for (std::size_t r = 0; r < ra.rows(); ++r) {
    for (std::size_t k = 0; k < ra.columns(); ++k) {
      const double x = ra.At(r, static_cast<int>(k)), y = rb.At(r, static_cast<int>(k));
      ASSERT_TRUE((std::isnan(x) && std::isnan(y)) || x == y) << ra.names()[k] << " row " << r;
    }
    differs_from_other_seed |= ra.At(r, col) != c->recorder().At(r, col);
  }
  EXPECT_TRUE(differs_from_other_seed);
}

TEST(VelocityExperiment, FusedSpeedBeatsOdometryWhenWheelsSlipOnLowFriction) {
  // Wet floor (μ = 0.15) and a 1 % wheel-radius calibration error: the odometry reads the
  // spinning wheels; the fused estimate sees the true motion through camera and IMU.
  auto exp = RunToEnd(LoadExperiment(kScenarios + "velocity_linear_low.yaml",
                                     {"duration=15", "estimator.vi_baseline=false"}));
  const VelocityExperiment& v = Vel(exp);
  for (int i = 0; i < v.robot_count(); ++i) {
    const RobotUnit& u = v.unit(i);
    std::printf("%s: speed RMSE odometry %.4f fused %.4f; Δv_c %.4f\n", u.spec.name.c_str(),
                u.total.odo.rms(), u.total.fused.rms(),
                std::abs(u.total.distance - u.total.v_cmd_int) / u.total.time);
    EXPECT_GT(u.total.odo.rms(), 0.008) << u.spec.name;  // the wheels really slip
    EXPECT_LT(u.total.fused.rms(), 0.7 * u.total.odo.rms()) << u.spec.name;
  }
  // The robot whose speed loop uses the fused estimate holds the commanded speed better.
  auto err = [&](int i) {
    const FloorStats& s = v.unit(i).total;
    return std::abs(s.distance - s.v_cmd_int) / s.time;
  };
  ASSERT_EQ(v.unit(0).spec.feedback, static_cast<int>(Feedback::kFused));
  ASSERT_EQ(v.unit(1).spec.feedback, static_cast<int>(Feedback::kOdometry));
  EXPECT_LT(err(0), 0.6 * err(1));
}

TEST(VelocityExperiment, PidTracksASpeedStepWithoutSteadyStateError) {
  for (const char* feedback : {"odometry", "fused"}) {
    auto exp = RunToEnd(OneRobot(std::string(R"(
duration: 9
world: {floor_friction: 0.9}
terrain: {floor: {rolling_resistance: 0.02, shear_slip: 0.03}}
sensors: {encoders: {radius_error: 0.0}}
command: {type: steps, start_delay: 0.5, steps: [{t: 0, v: 0.3}, {t: 3, v: 0.6}]}
robots: [{name: R1, pose: [0, 0, 0], feedback: )") +
                                 feedback + "}]\n"));
    const Recorder& rec = exp->recorder();
    const int t = rec.Column("t"), v = rec.Column("R1.v_true"), fb = rec.Column("R1.v_feedback");
    double sum_v = 0, sum_fb = 0;
    int n = 0;
    double v_after_1s = 0;
    for (std::size_t r = 0; r < rec.rows(); ++r) {
      const double time = rec.At(r, t);
      if (time >= 7.0) {
        sum_v += rec.At(r, v);
        sum_fb += rec.At(r, fb);
        ++n;
      }
      if (std::abs(time - 4.5) < 1e-9) v_after_1s = rec.At(r, v);
    }
    ASSERT_GT(n, 50);
    // The measured speed settles on the command (integral action), and so does the true speed
    // up to the small slip of a grippy floor.
    EXPECT_NEAR(sum_fb / n, 0.6, 0.002) << feedback;
    EXPECT_NEAR(sum_v / n, 0.6, 0.006) << feedback;
    EXPECT_GT(v_after_1s, 0.57) << feedback;  // 1 s after the step it is within 5 %
  }
}

TEST(VelocityExperiment, EstimatorFaultBecomesAnEventWithRobotAndTime) {
  // An absurd accelerometer bias overflows the IMU residuals.
  auto exp = RunToEnd(OneRobot(R"(
duration: 1.5
sensors: {imu: {accel_bias: [1.0e300, 0.0]}}
robots: [{name: R7, pose: [0, 0, 0], feedback: fused}]
)"));
  int faults = 0;
  for (const Event& e : exp->events())
    if (e.kind == "filter_fault") {
      ++faults;
      EXPECT_EQ(e.robots, "R7");
      EXPECT_NE(e.message.find("t="), std::string::npos);
    }
  EXPECT_GT(faults, 0);
  const Recorder& rec = exp->recorder();
  const int c = rec.Column("R7.v_fused");
  for (std::size_t r = 0; r < rec.rows(); ++r) EXPECT_TRUE(std::isfinite(rec.At(r, c)));
}

TEST(VelocityExperiment, FeedbackSwitchIsLiveAndDoesNotKick) {
  // An 8 % radius error: odometry and fused speed differ by a few cm/s when switching.
  auto exp = OneRobot(R"(
duration: 8
world: {floor_friction: 0.15}
sensors: {encoders: {radius_error: 0.08}}
command: {type: constant, v: 0.5}
robots: [{name: R1, pose: [0, 0, 0], feedback: odometry}]
)");
  while (exp->time() < 5.0 - 1e-9) exp->Step();
  const VelocityExperiment& v = Vel(exp);
  const RobotUnit& u = v.unit(0);
  const double jump = u.est_fused.v - u.odo.speed;
  ASSERT_GT(std::abs(jump), 0.02);
  PendingChanges change;
  change.edits.push_back({"robots.R1.feedback", "fused"});
  ASSERT_TRUE(exp->Apply(change).empty());
  const double u_before = u.drive->voltage(DiffDrive::kLeft);
  for (int k = 0; k < 4; ++k) exp->Step();  // one control period
  EXPECT_EQ(u.spec.feedback, static_cast<int>(Feedback::kFused));
  // Without compensation the voltage would jump by kp·|jump|; with it only the integral acts.
  const double kp = v.config().control.kp;
  EXPECT_LT(std::abs(u.drive->voltage(DiffDrive::kLeft) - u_before), 0.4 * kp * std::abs(jump));
}

// Every tests/fixtures/invalid/velocity_*.yaml starts with "# expect: <text>"; loading it must
// throw a ScenarioError containing the text and pointing at a line holding the offending key.
TEST(VelocityExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  const std::filesystem::path dir = std::string(FORMSIM_SOURCE_DIR) + "/tests/fixtures/invalid";
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string file = entry.path().string(), stem = entry.path().filename().string();
    if (stem.rfind("velocity_", 0) != 0) continue;
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    ASSERT_EQ(first.rfind("# expect: ", 0), 0u) << file;
    const std::string expect = first.substr(10);
    try {
      LoadExperiment(file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const ScenarioError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(expect), std::string::npos) << file << "\n  got: " << what;
      EXPECT_EQ(what.rfind(file + ":", 0), 0u) << what;
      ASSERT_GT(e.line(), 0) << what;
      std::ifstream again(file);
      std::string line;
      for (int k = 0; k < e.line(); ++k) std::getline(again, line);
      const std::string key = e.key().substr(e.key().rfind('.') + 1);
      EXPECT_NE(line.find(key.substr(0, key.find('['))), std::string::npos)
          << what << "\n  line: " << line;
    }
    ++checked;
  }
  EXPECT_GE(checked, 8);
}

// A draw sink that counts what it is asked to draw.
struct CountingSink : DrawSink {
  int polygons = 0, circles = 0, segments = 0, texts = 0;
  void Polygon(const std::vector<Vec2>&, Color, Color) override { ++polygons; }
  void Circle(Vec2, double, Color, Color) override { ++circles; }
  void Segment(Vec2, Vec2, Color, float) override { ++segments; }
  void Polyline(const std::vector<Vec2>&, Color, float, bool) override {}
  void CovarianceEllipse(Vec2, double, double, double, double, Color) override {}
  void Cross(Vec2, double, Color) override {}
  void Text(Vec2, const std::string&, Color, float, float) override { ++texts; }
  void Flash(Vec2, double, Color, float) override {}
};

TEST(VelocityExperiment, DrawsWindowKeyframesAndTrackedLandmarks) {
  auto exp = RunToEnd(OneRobot("duration: 4\nrobots: [{name: R1, pose: [0, 0, 0]}]\n"));
  const VelocityExperiment& v = Vel(exp);
  CountingSink sink;
  exp->Draw(sink);
  int tracked = 0;
  for (const auto& l : v.unit(0).fused.Landmarks()) tracked += l.initialized ? 1 : 0;
  EXPECT_GT(tracked, 3);
  // Landmarks of the map + window keyframes + tracked landmarks, each a circle.
  EXPECT_GE(sink.circles,
            static_cast<int>(v.landmarks().size() + v.unit(0).fused.window().size()) + tracked);
  EXPECT_GT(sink.texts, 0);
}

}  // namespace
}  // namespace formsim::sim::vio
