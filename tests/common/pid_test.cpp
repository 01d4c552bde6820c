// The PID loops with closed-form outputs: every term (P, I, D), the clamping, the anti-windup and
// the integral limit, in both forms. Each test fails on a sign flip or a removal of the term it
// names (the shipped scenarios all have kd = 0, so nothing else exercises the derivative).
#include <gtest/gtest.h>

#include <vector>

#include "control/common/pid.hpp"

namespace formsim::control {
namespace {

PidGains Gains(double kp, double ki, double kd) {
  PidGains g;
  g.kp = kp;
  g.ki = ki;
  g.kd = kd;
  return g;
}

std::vector<double> RunIncremental(IncrementalPid& pid, const std::vector<double>& errors) {
  std::vector<double> out;
  for (double e : errors) out.push_back(pid.Step(e));
  return out;
}

std::vector<double> RunPositional(Pid& pid, const std::vector<double>& errors, double dt) {
  std::vector<double> out;
  for (double e : errors) out.push_back(pid.Step(e, dt));
  return out;
}

// Δu = e_k − 2e_{k−1} + e_{k−2}: on 0, 1, 1, 0 the increments are 0, 1, −1, −1.
TEST(IncrementalPid, DerivativeTermAloneGivesTheSecondDifferenceSummed) {
  IncrementalPid pid(Gains(0, 0, 1));
  EXPECT_EQ(RunIncremental(pid, {0, 1, 1, 0}), (std::vector<double>{0, 1, 0, -1}));
}

TEST(IncrementalPid, ProportionalTermFollowsTheErrorAndIntegralTermSumsIt) {
  IncrementalPid p(Gains(2, 0, 0));
  EXPECT_EQ(RunIncremental(p, {0, 1, 1, 0}), (std::vector<double>{0, 2, 2, 0}));
  IncrementalPid i(Gains(0, 0.5, 0));
  EXPECT_EQ(RunIncremental(i, {0, 1, 1, 0}), (std::vector<double>{0, 0.5, 1, 1}));
}

TEST(IncrementalPid, TheStoredOutputIsTheClampedOneSoItLeavesTheLimitAtOnce) {
  PidGains g = Gains(0, 1, 0);
  g.out_max = 1;
  g.out_min = -1;
  IncrementalPid pid(g);
  // Three steps of +1 would sum to 3 unclamped; the first −1 must bring it off the limit at once.
  EXPECT_EQ(RunIncremental(pid, {1, 1, 1, -1}), (std::vector<double>{1, 1, 1, 0}));
}

// de/dt is 0 on the first step (no previous error), then (e_k − e_{k−1}) / dt.
TEST(Pid, DerivativeTermIsTheBackwardDifferenceOverDt) {
  Pid pid(Gains(0, 0, 1));
  EXPECT_EQ(RunPositional(pid, {0, 1, 1, 0}, 0.25), (std::vector<double>{0, 4, 0, -4}));
  pid.Reset();
  EXPECT_EQ(pid.Step(1, 0.25), 0) << "after Reset there is no previous error to differentiate";
}

TEST(Pid, ProportionalAndIntegralTermsAreExact) {
  Pid pid(Gains(2, 1, 0));
  // u = 2e + ∫e: the integral includes this step's e·dt (0.25, 0.5, 0.75).
  EXPECT_EQ(RunPositional(pid, {1, 1, 1}, 0.25), (std::vector<double>{2.25, 2.5, 2.75}));
  EXPECT_EQ(pid.integral(), 0.75);
}

// Clamping anti-windup: while the output is saturated in the direction of the error the integral
// stops growing, so when the error reverses the output leaves the limit at once.
TEST(Pid, AntiWindupHoldsTheIntegralAtTheOutputLimit) {
  PidGains g = Gains(0, 1, 0);
  g.out_max = 1;
  g.out_min = -1;
  Pid pid(g);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(pid.Step(1, 0.25), 0.25 * (k + 1));
  EXPECT_FALSE(pid.saturated());
  for (int k = 0; k < 6; ++k) EXPECT_EQ(pid.Step(1, 0.25), 1);
  EXPECT_TRUE(pid.saturated());
  EXPECT_EQ(pid.integral(), 1) << "held at ki·∫e = out_max, not 2.5";
  // Without anti-windup the integral would be 2.5 and the output would stay at 1 for six steps.
  EXPECT_EQ(pid.Step(-1, 0.25), 0.75);
  EXPECT_FALSE(pid.saturated());
}

TEST(Pid, IntegralLimitBoundsKiTimesTheIntegral) {
  PidGains g = Gains(0, 2, 0);
  g.integral_limit = 1;
  Pid pid(g);
  for (int k = 0; k < 10; ++k) pid.Step(1, 0.25);
  EXPECT_EQ(pid.integral(), 0.5);
  EXPECT_EQ(pid.Step(0, 0.25), 1);
  for (int k = 0; k < 10; ++k) pid.Step(-1, 0.25);
  EXPECT_EQ(pid.integral(), -0.5);
}

}  // namespace
}  // namespace formsim::control
