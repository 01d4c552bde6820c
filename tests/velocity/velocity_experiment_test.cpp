// The velocity-control experiment end to end: every scenario runs, runs are deterministic, the
// fused estimate beats odometry when the wheels slip (seeded), the PID holds a speed step
// without steady-state error, filter faults become events, the feedback source switches live
// (through sim::Session) without a kick and with its channels and summary entries, the
// tunables keep their keys, and bad scenarios are rejected.
#include "sim/velocity/velocity_experiment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "control/common/angle.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/session/session.hpp"
#include "tests/support/invalid_fixtures.hpp"

// Built with AddressSanitizer (scripts/sanitize.sh)?
#if defined(__SANITIZE_ADDRESS__)
#define FORMSIM_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FORMSIM_TEST_ASAN 1
#endif
#endif

namespace formsim::sim::velocity {
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
const char* kOneRobot = R"(
type: velocity
seed: 3
dt: 0.005
record_every: 2
landmarks: {count: 300, area: [-4, -6, 16, 6]}
estimator: {vi_baseline: false}
)";

std::unique_ptr<Experiment> OneRobot(const std::string& extra) {
  return LoadExperimentFromText(kOneRobot + extra, "inline.yaml");
}

TEST(VelocityExperiment, EveryScenarioLoadsAndRuns) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenarios)) {
    const std::string stem = entry.path().filename().string();
    if (stem.rfind("velocity_", 0) != 0) continue;
    // Each scenario with every landmark parameterisation, and without the side-slip constraint.
    for (const char* set :
         {"estimator.landmarks=world_point", "estimator.landmarks=inverse_depth_1d",
          "estimator.nonholonomic=false"}) {
      auto other = RunToEnd(LoadExperiment(entry.path().string(), {"duration=1.5", set}));
      for (int i = 0; i < Vel(other).robot_count(); ++i) {
        EXPECT_GT(Vel(other).unit(i).updates, 3) << stem << " " << set;
        EXPECT_EQ(Vel(other).unit(i).faults, 0) << stem << " " << set;
      }
    }
    auto exp = RunToEnd(LoadExperiment(entry.path().string(), {"duration=1.5"}));
    EXPECT_EQ(exp->setup().type, "velocity") << stem;
    EXPECT_FALSE(exp->setup().description.empty()) << stem;
    const VelocityExperiment& v = Vel(exp);
    for (int i = 0; i < v.robot_count(); ++i) {
      EXPECT_GT(v.unit(i).updates, 3) << stem;
      EXPECT_EQ(v.unit(i).faults, 0) << stem;
    }
    EXPECT_FALSE(exp->Summary().Dump().empty());
    EXPECT_FALSE(exp->Figures().empty());
    // Every figure series names a recorded column.
    for (const FigureSpec& f : exp->Figures())
      for (const SeriesSpec& s : f.series) {
        if (!s.column.empty()) {
          EXPECT_GE(exp->recorder().Column(s.column), 0) << f.id << " " << s.column;
        }
        if (!s.x_column.empty()) {
          EXPECT_GE(exp->recorder().Column(s.x_column), 0) << f.id << " " << s.x_column;
        }
      }
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

// Fig. 5-6's claim on velocity_constant, over seeds: the fused speed estimate beats both the
// visual-inertial-only one and wheel odometry (which reads the wheels' slip on wet and gravel).
// Only the robot whose loop uses the fused estimate; the whole 40 s, since the gravel where
// odometry goes wrong comes after 22 s. Measured on seeds 1-3 (inverse depth): fused 0.0081-
// 0.0082, VI-only 0.0083-0.0129, odometry 0.0149 m/s.
TEST(VelocityExperiment, FusedBeatsVisualInertialAndOdometryOnVelocityConstant) {
#ifdef FORMSIM_TEST_ASAN
  // Three 40 s runs of two sliding windows take minutes under the sanitizer; the same code
  // paths run there in the shorter velocity tests, this claim is checked in the Release suite.
  GTEST_SKIP() << "a numerical claim over three full runs: checked in the Release suite";
#endif
  std::ifstream in(kScenarios + "velocity_constant.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string odo_robot = "  - {name: R_odo, pose: [0.0, -1.5, 0.0], feedback: odometry}\n";
  const auto at = text.find(odo_robot);
  ASSERT_NE(at, std::string::npos);
  text.erase(at, odo_robot.size());
  double fused = 0.0, vi = 0.0, odo = 0.0;
  const int seeds[] = {1, 2, 3};
  for (int seed : seeds) {
    auto exp = RunToEnd(LoadExperimentFromText(text, "velocity_constant.yaml", {}, seed));
    const VelocityExperiment& v = Vel(exp);
    ASSERT_EQ(v.robot_count(), 1);
    const FloorStats& s = v.unit(0).total;
    EXPECT_EQ(v.unit(0).faults, 0) << seed;
    EXPECT_LT(s.fused.rms(), s.odo.rms()) << "seed " << seed;
    std::printf("seed %d: speed RMSE fused %.4f, VI-only %.4f, odometry %.4f\n", seed,
                s.fused.rms(), s.vi.rms(), s.odo.rms());
    fused += s.fused.rms() / 3.0;
    vi += s.vi.rms() / 3.0;
    odo += s.odo.rms() / 3.0;
  }
  EXPECT_LT(fused, 0.9 * vi);
  EXPECT_LT(vi, odo);
  EXPECT_LT(fused, 0.7 * odo);
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
    // up to the small slip of a grippy floor, or up to the fused estimate's own error (its
    // visual scale is 1-3 % off on seeds 1-5, with either landmark parameterisation).
    EXPECT_NEAR(sum_fb / n, 0.6, 0.002) << feedback;
    EXPECT_NEAR(sum_v / n, 0.6, std::string(feedback) == "fused" ? 0.02 : 0.006) << feedback;
    EXPECT_GT(v_after_1s, 0.57) << feedback;  // 1 s after the step it is within 5 %
  }
}

TEST(VelocityExperiment, EstimatorFaultBecomesAnEventWithRobotAndTime) {
  // An absurd accelerometer offset (no valid scenario can give one: accel_bias is bounded)
  // overflows the IMU residuals.
  auto exp = OneRobot(R"(
duration: 1.5
robots: [{name: R7, pose: [0, 0, 0], feedback: fused}]
)");
  dynamic_cast<VelocityExperiment&>(*exp).OffsetEstimatorImuForTest(0, 1e300);
  exp = RunToEnd(std::move(exp));
  int faults = 0;
  for (const Event& e : exp->events().list())
    if (e.kind == "filter_fault") {
      ++faults;
      EXPECT_EQ(e.robots, "R7");
      EXPECT_NE(e.message.find("t="), std::string::npos);
    }
  EXPECT_GT(faults, 0);
  // One event per run of faults (the fused estimator faults at every update here), every fault
  // counted.
  EXPECT_EQ(faults, 1);
  const RobotUnit& u = Vel(exp).unit(0);
  EXPECT_GT(u.faults, faults);
  const Metrics m = exp->Results();
  ASSERT_NE(m.Find("robots.R7.estimator_faults"), nullptr);
  EXPECT_EQ(*m.Find("robots.R7.estimator_faults"), static_cast<double>(u.faults));
  EXPECT_EQ(*m.Find("robots.R7.events.filter_fault"), static_cast<double>(faults));
  const Recorder& rec = exp->recorder();
  const int c = rec.Column("R7.v_fused");
  for (std::size_t r = 0; r < rec.rows(); ++r) EXPECT_TRUE(std::isfinite(rec.At(r, c)));
}

TEST(VelocityExperiment, FeedbackSwitchIsLiveAndDoesNotKick) {
  // An 8 % radius error: odometry and fused speed differ by a few cm/s when switching.
  Session s(kScenarios + "velocity_linear_low.yaml",
            {"duration=8", "estimator.vi_baseline=false", "sensors.encoders.radius_error=0.08"},
            -1);
  while (s.exp().time() < 5.0 - 1e-9) s.Step();
  const auto& v = dynamic_cast<const VelocityExperiment&>(s.exp());
  const RobotUnit& u = v.unit(1);
  ASSERT_EQ(u.spec.name, "R_odo");
  const double jump = u.est_fused.v - u.odo.speed;
  ASSERT_GT(std::abs(jump), 0.02);
  ASSERT_EQ(s.Edit("robots.R_odo.feedback", "fused"), "");
  const double u_before = u.drive->voltage(DiffDrive::kLeft);
  for (int k = 0; k < 4; ++k) s.Step();  // one control period
  EXPECT_EQ(u.spec.feedback, static_cast<int>(Feedback::kFused));
  // Without compensation the voltage would jump by kp·|jump|; with it only the integral acts.
  const double kp = v.config().control.kp;
  std::printf("feedback switch: estimate jump %.4f m/s, left voltage %.3f -> %.3f V\n", jump,
              u_before, u.drive->voltage(DiffDrive::kLeft));
  EXPECT_LT(std::abs(u.drive->voltage(DiffDrive::kLeft) - u_before), 0.4 * kp * std::abs(jump));
}

// The live choice (each robot's feedback source) switched mid-run, both ways: from the next
// control step the speed loop's recorded input (v_feedback) is the newly chosen estimate, the
// feedback channel says which, and the summary names the source in use.
TEST(VelocityExperiment, FeedbackSwitchedMidRunShowsInChannelsAndSummary) {
  Session s(kScenarios + "velocity_linear_low.yaml", {"duration=4"}, -1);
  const double t_switch = 1.5;
  while (s.exp().time() < t_switch - 1e-9) s.Step();
  ASSERT_EQ(s.Edit("robots.R_fused.feedback", "odometry"), "");
  ASSERT_EQ(s.Edit("robots.R_odo.feedback", "fused"), "");
  while (!s.exp().finished()) s.Step();
  // Control, encoders and records share a 4-step grid here: the input recorded in a row is the
  // estimate recorded in the row before.
  const Recorder& rec = s.exp().recorder();
  const int ct = rec.Column("t");
  for (const std::string robot : {"R_fused", "R_odo"}) {
    const int cfb = rec.Column(robot + ".v_feedback"), cmode = rec.Column(robot + ".feedback");
    const int codo = rec.Column(robot + ".v_odo"), cfused = rec.Column(robot + ".v_fused");
    const double before = robot == "R_fused" ? 1.0 : 0.0;
    int switched_rows = 0;
    for (std::size_t r = 1; r < rec.rows(); ++r) {
      const bool after = rec.At(r, ct) > t_switch + 1e-9;
      const double mode = after ? 1.0 - before : before;
      switched_rows += after;
      ASSERT_EQ(rec.At(r, cmode), mode) << robot << " t = " << rec.At(r, ct);
      ASSERT_EQ(rec.At(r, cfb), rec.At(r - 1, mode == 1.0 ? cfused : codo))
          << robot << " t = " << rec.At(r, ct);
    }
    EXPECT_GT(switched_rows, 100) << robot;
  }
  const Metrics m = s.exp().Results();
  EXPECT_EQ(m.Cell("robots.R_fused.feedback", ""), "odometry");
  EXPECT_EQ(m.Cell("robots.R_odo.feedback", ""), "fused");
  // Both estimates are scored whichever source is chosen.
  for (const std::string robot : {"R_fused", "R_odo"})
    for (const char* path : {".speed_rmse.odometry", ".speed_rmse.fused", ".speed_rmse.vi_only",
                             ".control.linear_error"})
      EXPECT_NE(m.Find("robots." + robot + path), nullptr) << robot << path;
  EXPECT_NE(s.exp().Summary().Dump().find("\"odometry\""), std::string::npos);
}

// The tunables keep the keys, groups, sliders and live/reset behaviour they had.
TEST(VelocityExperiment, TunablesAreYamlPathsWithTheirDeclarations) {
  Session s(kScenarios + "velocity_constant.yaml", {}, -1);
  const ParamTable& p = s.params();
  for (const char* key : {"control.kp",
                          "control.ki",
                          "control.kd",
                          "robots.R_fused.feedback",
                          "robots.R_odo.feedback",
                          "command.v",
                          "command.omega",
                          "sensors.encoders.angle_noise",
                          "sensors.encoders.radius_error",
                          "sensors.encoders.track_error",
                          "sensors.imu.gyro_noise_density",
                          "sensors.imu.accel_noise_density",
                          "sensors.imu.gyro_bias",
                          "sensors.imu.gyro_bias_rw",
                          "sensors.imu.accel_bias_rw",
                          "sensors.camera.bearing_noise",
                          "sensors.camera.fov_deg",
                          "sensors.camera.range",
                          "sensors.camera.max_features",
                          "world.floor_friction",
                          "terrain.floor.rolling_resistance",
                          "terrain.floor.shear_slip",
                          "patches.wet.friction",
                          "terrain.wet.rolling_resistance",
                          "terrain.wet.shear_slip",
                          "terrain.asphalt.shear_slip",
                          "estimator.odometry.speed_noise_density",
                          "estimator.odometry.yaw_rate_noise_density",
                          "estimator.odometry.speed_bias_rw",
                          "estimator.odometry.yaw_rate_bias_rw",
                          "estimator.nonholonomic_sigma",
                          "estimator.min_parallax_deg",
                          "estimator.window_size",
                          "estimator.keyframe_every",
                          "estimator.landmarks",
                          "estimator.nonholonomic"})
    ASSERT_NE(p.Find(key), nullptr) << key;
  EXPECT_EQ(p.size(),
            41u);  // the 36 above and the friction and terrain of gravel, asphalt μ and rr
  EXPECT_EQ(p.Find("estimator.landmarks")->Text(), "inverse_depth");
  for (const char* key : {"estimator.window_size", "estimator.keyframe_every",
                          "estimator.landmarks", "patches.gravel.friction"})
    EXPECT_FALSE(p.Find(key)->tune.live) << key;
  EXPECT_TRUE(p.Find("robots.R_odo.feedback")->tune.live);
  EXPECT_EQ(p.Find("control.kp")->tune.group, "Gains/speed PID");
  EXPECT_EQ(p.Find("control.kp")->slider_max(), 20.0);
  EXPECT_EQ(p.Find("sensors.camera.fov_deg")->value, 90.0);
  EXPECT_EQ(p.Find("terrain.gravel.shear_slip")->value, 0.25);
  EXPECT_EQ(p.Find("robots.R_odo.feedback")->Text(), "odometry");
  // A steps command is a script: its v and ω are not tunables.
  Session steps(kScenarios + "velocity_steps.yaml", {}, -1);
  EXPECT_EQ(steps.params().Find("command.v"), nullptr);
  // Edits are checked by the loader's rules; live ones reach the running experiment.
  EXPECT_NE(s.Edit("sensors.camera.fov_deg", "400").find("must be in (0, 360)"), std::string::npos);
  EXPECT_EQ(s.Edit("control.kp", "5"), "");
  EXPECT_EQ(s.Edit("sensors.camera.fov_deg", "60"), "");
  EXPECT_EQ(s.Edit("estimator.window_size", "6"), "");  // waits for a reset
  s.Step();
  const auto& v = dynamic_cast<const VelocityExperiment&>(s.exp());
  EXPECT_EQ(v.unit(0).loop.def().gains.kp, 5.0);
  EXPECT_NEAR(v.unit(1).camera.def().fov, control::kPi / 3, 1e-15);
  EXPECT_EQ(v.unit(0).fused.def().window_size, 10);
  EXPECT_EQ(s.waiting_for_reset().count("estimator.window_size"), 1u);
  EXPECT_EQ(s.Reset(), "");
  EXPECT_EQ(dynamic_cast<const VelocityExperiment&>(s.exp()).unit(0).fused.def().window_size, 6);
}

// A period shorter than one world step is an error, never zero steps per sample.
TEST(VelocityExperiment, RatesAreCheckedAgainstTheWorldStep) {
  try {
    LoadExperimentFromText("type: velocity\ndt: 0.01\nduration: 1\nsensors: {imu: {rate: 400}}\n");
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.key(), "sensors.imu.rate");
    EXPECT_NE(std::string(e.what()).find("at least one world step"), std::string::npos) << e.what();
  }
  // Rates that are not a whole number of steps round, as before.
  auto exp = OneRobot("duration: 0.1\nsensors: {camera: {rate: 30}}\nrobots: [{name: R1}]\n");
  EXPECT_EQ(Vel(exp).config().every.camera, 7);
}

// Every tests/fixtures/invalid/velocity_*.yaml starts with "# expect: <text>"; loading it must
// throw a ScenarioError containing the text and pointing at a line holding the offending key.
TEST(VelocityExperiment, InvalidFixturesAreRejectedWithTheRightMessage) {
  EXPECT_GE(formsim::testing::CheckInvalidFixtures("velocity_"), 15);
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
}  // namespace formsim::sim::velocity
