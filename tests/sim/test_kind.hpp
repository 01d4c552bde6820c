#pragma once
// A minimal experiment kind for the core tests: one unicycle on a circle with a noisy speed
// sensor. It is also the smallest example of a kind: a config with its strict reader (which
// declares the tunables), a constructor, the loop hooks, channels and results.
#include "sim/core/experiment.hpp"
#include "sim/core/unicycle_drive.hpp"

#include <cmath>
#include <limits>

namespace formsim::sim::testkind {

struct CircleConfig {
  double v = 1.0, omega = 0.5, sigma = 0.1, v_max_sum = 10.0;
  /// For the fault tests: at fault_time, make the measured speed (value) or the robot's
  /// velocity (state) non-finite.
  int fault = 0;  ///< 0 none, 1 value, 2 state
  double fault_time = 0.5;
  UnicycleDriveDef drive;
};

class NoisyCircle : public ExperimentOf<CircleConfig> {
 public:
  static CircleConfig ReadConfig(YamlReader& root, const ExperimentSetup&) {
    CircleConfig c;
    c.v = root.Real("v", c.v, Tune("v", "m/s").AtLeast(0).Slider(0.0, 3.0).Group("Gains/R1"));
    c.omega = root.Real("omega", c.omega, Tune("ω", "rad/s").In(-5, 5).Slider(-2.0, 2.0).Group("Gains/R1"));
    c.sigma = root.Real("sigma", c.sigma, Tune("σ", "m/s").AtLeast(0).Slider(0.0, 1.0).Group("Noise/R1").OnReset());
    // A rule across keys, as the formation's triangle check: |v| + |ω| must stay below 4.
    if (std::abs(c.v) + std::abs(c.omega) >= 4.0) root.Fail("omega", "v + |omega| must be < 4");
    YamlReader drive = root.Map("drive");
    c.drive = ReadUnicycleDrive(drive, "Drive/R1");
    c.fault = root.Choice("fault", {"none", "value", "state"}, 0);
    c.fault_time = root.Double("fault_time", c.fault_time);
    return c;
  }
  NoisyCircle(const ExperimentSetup& s, const CircleConfig& c) : ExperimentOf(s, c) {
    RobotDef def = DefaultRobotDef();
    def.name = "R1";
    robot_ = &world_.CreateRobot(def);
    auto d = std::make_unique<UnicycleDrive>(cfg_.drive);
    drive_ = d.get();
    robot_->SetDrive(std::move(d));
    sensor_ = rng_.Fork(1);
    recorder_.AddGroup({"x", "y"}, [this](double* o) {
      o[0] = robot_->pose().x;
      o[1] = robot_->pose().y;
    });
    recorder_.Add("measured_v", [this] { return measured_; });
    Start();
  }
  std::vector<FigureSpec> Figures() const override {
    return {TimeFigure("speed", "Speed", "v [m/s]", {Line("measured", "measured_v")})};
  }
  Metrics Results() const override {
    Metrics m;
    m.Set("x", robot_->pose().x);
    m.SetText("mode", "circle");
    return m;
  }
  double v() const { return cfg_.v; }
  double sigma() const { return cfg_.sigma; }

 protected:
  void Control(double t) override {
    drive_->SetCommand(cfg_.v, cfg_.omega);
    // A drive that blows up: Box2D integrates an infinite force into the state.
    if (cfg_.fault == 2 && t >= cfg_.fault_time)
      robot_->body()->ApplyForceToCenter(b2Vec2(std::numeric_limits<float>::infinity(), 0), true);
  }
  void Sense(double t) override {
    measured_ = robot_->forward_speed() + sensor_.Normal(0, cfg_.sigma);
    if (cfg_.fault == 1 && t >= cfg_.fault_time) measured_ = std::nan("");
  }
  void DrawScene(DrawSink&) const override {}
  void ApplyTunables(const CircleConfig& next) override {
    const double sigma = cfg_.sigma;  // OnReset: must not change here
    cfg_ = next;
    cfg_.sigma = sigma;
    drive_->def() = cfg_.drive;
  }

 private:
  Robot* robot_ = nullptr;
  UnicycleDrive* drive_ = nullptr;
  Rng sensor_;
  double measured_ = 0;
};

inline const char* kScenario =
    "# A circle for the core tests\n"
    "type: test_noisy_circle\nname: circle\nseed: 3\ndt: 0.01\nduration: 1.0\n"
    "v: 1.2   # forward speed\nomega: 0.5\nsigma: 0.1\ndrive: {mode: ideal}\n";

}  // namespace formsim::sim::testkind
