// The wheel speed loop (incremental PID per wheel, Δv_s compensation), the paper's fused speed
// strategy between optimiser updates, and command profiles.
#include "control/velocity/speed_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/velocity/command_profile.hpp"
#include "control/velocity/fused_speed.hpp"

namespace cv = formsim::control::velocity;

TEST(SpeedLoop, WheelKinematicsRoundTrip) {
  const cv::WheelSpeeds w = cv::ToWheelSpeeds(0.5, 0.8, 0.3);
  EXPECT_DOUBLE_EQ(w.left, 0.5 - 0.12);
  EXPECT_DOUBLE_EQ(w.right, 0.5 + 0.12);
  EXPECT_DOUBLE_EQ(cv::BodySpeed(w), 0.5);
  EXPECT_NEAR(cv::BodyYawRate(w, 0.3), 0.8, 1e-12);
}

TEST(SpeedLoop, CompensationRemovesTheProportionalKickOfAnEstimateJump) {
  cv::SpeedLoopDef d;
  d.gains.kp = 4.0;
  d.gains.ki = 0.5;
  cv::WheelSpeedLoop plain(d), compensated(d);
  for (int k = 0; k < 20; ++k) {
    plain.Step(0.5, 0.0, 0.45, 0.0);
    compensated.Step(0.5, 0.0, 0.45, 0.0);
  }
  // The estimate jumps up by 0.03 m/s (an optimiser update), the robot did not change.
  const double u_before = plain.Step(0.5, 0.0, 0.45, 0.0).u_left;
  compensated.Step(0.5, 0.0, 0.45, 0.0);
  const double u_plain = plain.Step(0.5, 0.0, 0.48, 0.0).u_left;
  compensated.CompensateEstimateJump(0.03, 0.0);
  const double u_comp = compensated.Step(0.5, 0.0, 0.48, 0.0).u_left;
  // Without compensation the P term kicks by -kp·0.03; with it only the I term acts (ki·e).
  EXPECT_NEAR(u_plain - u_before, -4.0 * 0.03 + 0.5 * 0.02, 1e-12);
  EXPECT_NEAR(u_comp - u_before, 0.5 * 0.02, 1e-12);
}

TEST(SpeedLoop, IntegralActionRemovesSteadyStateErrorOnAFirstOrderPlant) {
  // Wheel speed responds to voltage with gain 0.08 (m/s)/V and time constant 60 ms; a constant
  // load takes 0.02 m/s. The incremental PID at 50 Hz must end without steady-state error.
  cv::SpeedLoopDef d;
  d.gains.kp = 3.0;
  d.gains.ki = 1.0;
  d.gains.out_min = -12.0;
  d.gains.out_max = 12.0;
  cv::WheelSpeedLoop loop(d);
  double v = 0.0;
  for (int k = 0; k < 300; ++k) {
    const auto out = loop.Step(0.4, 0.0, v, 0.0);
    const double target = 0.08 * out.u_left - 0.02;
    v += (target - v) * (1.0 - std::exp(-0.02 / 0.06));
  }
  EXPECT_NEAR(v, 0.4, 1e-4);
}

TEST(FusedSpeedEstimate, WindowSpeedAtUpdateThenBiasCorrectedOdometry) {
  cv::FusedSpeedEstimate f;
  EXPECT_DOUBLE_EQ(f.Estimate(0.5, 0.1).v, 0.5);  // no update yet: biases zero
  f.OnUpdate(0.47, 0.025, 0.01);
  EXPECT_DOUBLE_EQ(f.Peek(0.5, 0.1).v, 0.47);
  const cv::BodyTwist at_update = f.Estimate(0.5, 0.1);
  EXPECT_DOUBLE_EQ(at_update.v, 0.47);
  EXPECT_NEAR(at_update.omega, 0.09, 1e-12);
  const cv::BodyTwist next = f.Estimate(0.51, 0.1);
  EXPECT_NEAR(next.v, 0.51 - 0.025, 1e-12);
}

TEST(CommandProfile, StepsAndRamps) {
  cv::CommandProfile p({{1.0, 0.3, 0.0}, {5.0, 0.6, 0.5}});
  double v, w;
  p.At(0.5, v, w);
  EXPECT_EQ(v, 0.0);
  p.At(2.0, v, w);
  EXPECT_EQ(v, 0.3);
  p.At(5.0, v, w);
  EXPECT_EQ(v, 0.6);
  EXPECT_EQ(w, 0.5);
  cv::CommandProfile r({{0.0, 0.0, 0.0}, {1.0, 0.6, 0.0}}, 0.5);
  r.At(1.5, v, w);
  EXPECT_NEAR(v, 0.25, 1e-12);
  r.At(3.0, v, w);
  EXPECT_NEAR(v, 0.6, 1e-12);
}
