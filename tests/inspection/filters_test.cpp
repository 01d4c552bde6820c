// Per-axis Kalman filter (section 1.3) and the classical limit / mean filters.
#include <gtest/gtest.h>

#include <cmath>

#include "control/inspection/axis_kalman.hpp"
#include "control/inspection/classic_filters.hpp"
#include "control/inspection/dead_reckoning.hpp"
#include "sim/core/rng.hpp"

namespace ins = formsim::control::inspection;
using formsim::Vec2;

TEST(DeadReckoning, Eq1HeadingFromTheYAxis) {
  ins::PaperPose p{1.0, 2.0, 0.0};
  p = ins::DeadReckonStep(p, 1.0, 0.0);  // heading 0 is +Y
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 3.0, 1e-12);
  p = ins::DeadReckonStep(p, 2.0, M_PI / 2.0);  // heading 90° is +X
  EXPECT_NEAR(p.x, 3.0, 1e-12);
  EXPECT_NEAR(p.y, 3.0, 1e-12);
  const auto inc = ins::DifferentialOdometry(0.11, 0.09, 0.5);
  EXPECT_NEAR(inc.ds, 0.10, 1e-12);
  EXPECT_NEAR(inc.dtheta, 0.04, 1e-12);  // faster left wheel: clockwise, heading grows
}

// A static robot: noisy fixes around a fixed point, no motion. Both axes converge on the
// point and the variance shrinks like R/k.
TEST(AxisKalman, ConvergesOnAStaticRobot) {
  ins::AxisKalmanDef def;
  def.r = 0.05 * 0.05;
  def.p0 = 1.0;
  def.q_per_s = 0.0;
  ins::PositionKalman kf(def);
  kf.Reset({3.8, 9.4});  // 0.5 m and 0.6 m off
  const Vec2 truth{3.3, 10.0};
  formsim::sim::Rng rng(42);
  double last_p = kf.axis_x().P();
  for (int k = 0; k < 400; ++k) {
    ASSERT_TRUE(kf.Predict(0.0, 0.0, 0.02));
    const Vec2 z{truth.x + rng.Normal(0.0, 0.05), truth.y + rng.Normal(0.0, 0.05)};
    const auto r = kf.Update(z);
    ASSERT_FALSE(r.fault());
    EXPECT_LE(kf.axis_x().P(), last_p + 1e-15);
    last_p = kf.axis_x().P();
  }
  EXPECT_NEAR(kf.position().x, truth.x, 0.01);
  EXPECT_NEAR(kf.position().y, truth.y, 0.01);
  EXPECT_NEAR(kf.axis_x().P(), def.r / 400.0, def.r / 4000.0);
  EXPECT_LT(kf.axis_y().gain(), 0.01);
}

// The per-axis filter against the closed-form scalar recursion of section 1.3, step by step:
// P⁻ = P + q_per_m·|Δ| + q_per_s·Δt, K = P⁻ / (P⁻ + R), x = x⁻ + K (z − x⁻), P = (1 − K) P⁻,
// with motion along both axes (heading 30° from +Y), a varying step and R > 0. A fixed gain, a
// gain from the wrong variance or an update that skips the prediction's variance all fail it.
TEST(AxisKalman, StateVarianceAndGainFollowTheClosedForm) {
  ins::AxisKalmanDef def;
  def.q_per_m = 2e-4;
  def.q_per_s = 1e-5;
  def.r = 4e-3;
  def.p0 = 1e-2;
  def.nis_gate = 0.0;  // every fix accepted
  ins::PositionKalman kf(def);
  kf.Reset({3.3, 2.0});
  double x[2] = {3.3, 2.0}, P[2] = {def.p0, def.p0};
  const double theta = M_PI / 6.0;
  formsim::sim::Rng rng(3);
  for (int k = 0; k < 60; ++k) {
    const double ds = 0.004 + 0.002 * (k % 5), dt = 0.01 + 0.005 * (k % 3);
    ASSERT_TRUE(kf.Predict(ds, theta, dt));
    const double du[2] = {ds * std::sin(theta), ds * std::cos(theta)};
    for (int a = 0; a < 2; ++a) {
      x[a] += du[a];
      P[a] += def.q_per_m * std::abs(du[a]) + def.q_per_s * dt;
    }
    if (k % 4 != 3) continue;  // a fix every fourth step (odometry runs faster than the laser)
    const Vec2 z{x[0] + rng.Normal(0.0, 0.06), x[1] + rng.Normal(0.0, 0.06)};
    const auto r = kf.Update(z);
    ASSERT_EQ(r.x, ins::AxisUpdate::kAccepted);
    ASSERT_EQ(r.y, ins::AxisUpdate::kAccepted);
    const double zz[2] = {z.x, z.y};
    const ins::AxisKalman* axis[2] = {&kf.axis_x(), &kf.axis_y()};
    for (int a = 0; a < 2; ++a) {
      const double K = P[a] / (P[a] + def.r);
      x[a] += K * (zz[a] - x[a]);
      P[a] *= 1.0 - K;
      EXPECT_NEAR(axis[a]->gain(), K, 1e-12 * K) << "step " << k << " axis " << a;
      EXPECT_NEAR(axis[a]->P(), P[a], 1e-12 * P[a]) << "step " << k << " axis " << a;
      EXPECT_NEAR(axis[a]->x(), x[a], 1e-12) << "step " << k << " axis " << a;
    }
  }
  // The gain has settled well below the first one (the variance shrank from P0).
  EXPECT_LT(kf.axis_x().gain(), 0.5 * def.p0 / (def.p0 + def.r));
}

TEST(AxisKalman, PredictFollowsDeadReckoning) {
  ins::PositionKalman kf;
  kf.Reset({0.0, 0.0});
  const double p0 = kf.axis_x().P();
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(kf.Predict(0.01, M_PI / 6.0, 0.02));
  EXPECT_NEAR(kf.position().x, 0.5, 1e-12);  // 1 m at 30° from +Y
  EXPECT_NEAR(kf.position().y, std::sqrt(3.0) / 2.0, 1e-12);
  EXPECT_GT(kf.axis_x().P(), p0);
}

TEST(AxisKalman, GatesOutliersThenReacquires) {
  ins::AxisKalmanDef def;
  def.r = 1e-4;
  def.p0 = 1e-4;
  def.nis_gate = 9.0;
  def.reacquire_after = 5;
  ins::AxisKalman kf(def);
  kf.Reset(1.0);
  EXPECT_EQ(kf.Update(1.8), ins::AxisUpdate::kGated);
  EXPECT_NEAR(kf.x(), 1.0, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(kf.Update(1.8), ins::AxisUpdate::kGated);
  EXPECT_EQ(kf.Update(1.8), ins::AxisUpdate::kReinitialised);
  EXPECT_NEAR(kf.x(), 1.8, 1e-12);
  EXPECT_EQ(kf.Update(1.801), ins::AxisUpdate::kAccepted);
}

TEST(AxisKalman, NonFiniteInputIsAFaultNotANaN) {
  ins::PositionKalman kf;
  kf.Reset({1.0, 2.0});
  EXPECT_FALSE(kf.Predict(std::nan(""), 0.0, 0.02));
  EXPECT_TRUE(kf.Update({std::nan(""), 2.0}).fault());
  EXPECT_TRUE(std::isfinite(kf.position().x));
  EXPECT_NEAR(kf.position().x, 1.0, 1e-12);
  ins::AxisKalmanDef bad;
  bad.r = -1.0;  // a negative variance makes S negative: caught, not propagated
  bad.p0 = 0.5;
  ins::AxisKalman a(bad);
  a.Reset(0.0);
  const auto r = a.Update(0.4);
  EXPECT_TRUE(std::isfinite(a.x()));
  EXPECT_TRUE(r == ins::AxisUpdate::kFault || a.P() >= 0.0);
}

TEST(ClassicFilters, LimitRejectsJumpsAndMeanAverages) {
  ins::LimitFilterDef def;
  def.max_step = 0.3;
  def.max_rate = 0.0;
  def.reacquire_after = 3;
  ins::ClassicPositionFilter f(def, 4);
  EXPECT_TRUE(f.Filter({3.3, 10.0}, 0.0));
  EXPECT_TRUE(f.Filter({3.4, 10.0}, 0.02));
  EXPECT_NEAR(f.value().x, 3.35, 1e-12);
  EXPECT_FALSE(f.Filter({4.5, 10.0}, 0.04));  // a 1.1 m jump
  EXPECT_NEAR(f.value().x, 3.35, 1e-12);
  EXPECT_TRUE(f.Filter({3.5, 10.0}, 0.06));
  EXPECT_TRUE(f.Filter({3.6, 10.0}, 0.08));
  EXPECT_TRUE(f.Filter({3.7, 10.0}, 0.10));
  EXPECT_NEAR(f.value().x, (3.4 + 3.5 + 3.6 + 3.7) / 4.0, 1e-12);  // window of 4
  // A lasting jump is taken after `reacquire_after` rejections.
  EXPECT_FALSE(f.Filter({6.0, 10.0}, 0.12));
  EXPECT_FALSE(f.Filter({6.0, 10.0}, 0.14));
  EXPECT_FALSE(f.Filter({6.0, 10.0}, 0.16));
  EXPECT_TRUE(f.Filter({6.0, 10.0}, 0.18));
  EXPECT_EQ(f.rejected(), 4);
}

TEST(ClassicFilters, LimitWidensWithTheTimeSinceTheLastFix) {
  ins::LimitFilterDef def;
  def.max_step = 0.1;
  def.max_rate = 1.0;
  ins::ClassicPositionFilter f(def, 1);
  EXPECT_TRUE(f.Filter({0.0, 0.0}, 0.0));
  EXPECT_FALSE(f.Filter({0.5, 0.0}, 0.1));  // allowed 0.2 m
  EXPECT_TRUE(f.Filter({0.5, 0.0}, 1.0));   // allowed 1.1 m after a 1 s gap
}

TEST(HeadingFilter, LimitMeanAndMotionCompensation) {
  ins::HeadingFilterDef def;
  def.limit = 0.1;
  def.window = 3;
  def.reacquire_after = 100;
  ins::HeadingFilter f(def);
  f.Reset(0.0);
  EXPECT_TRUE(f.Update(0.02));
  EXPECT_TRUE(f.Update(-0.02));
  EXPECT_NEAR(f.value(), 0.0, 1e-12);
  EXPECT_FALSE(f.Update(0.5));  // a jump beyond the limit
  EXPECT_NEAR(f.value(), 0.0, 1e-12);
  // Turning by 0.05 rad: stored samples turn with the robot, so the mean does not lag.
  f.Propagate(0.05);
  EXPECT_NEAR(f.value(), 0.05, 1e-12);
  EXPECT_TRUE(f.Update(0.05));
  EXPECT_NEAR(f.value(), 0.05, 1e-12);
  // Across ±π the mean stays continuous.
  f.Reset(M_PI - 0.01);
  EXPECT_TRUE(f.Update(-M_PI + 0.01));
  EXPECT_NEAR(std::abs(f.value()), M_PI, 0.011);
}
