// The beacon/odometry Kalman filter: snapping, gating, adaptive R, angle wrap, faults.
#include "control/agv/pose_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/common/angle.hpp"
#include "control/agv/chi_square.hpp"
#include "tests/agv/test_noise.hpp"

namespace formsim::control::agv {
namespace {

TEST(ChiSquare, KnownQuantiles) {
  EXPECT_NEAR(ChiSquareQuantile(0.99, 3), 11.3449, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 1), 3.8415, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.999, 3), 16.2662, 1e-3);
  EXPECT_NEAR(ChiSquareCdf(2.366, 3), 0.5, 1e-3);
  EXPECT_NEAR(ChiSquareCdf(40.0, 3), 1.0, 1e-6);
}

TEST(PoseFilter, ZeroBeaconNoiseSnapsToBeacon) {
  PoseFilterDef def;
  def.r_xy = 0.0;
  def.r_theta = 0.0;
  def.gate = false;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  f.Predict({0.3, 0.0, 0.1}, 0.1);
  const Pose2 z{0.05, -0.02, 0.03};
  const FuseReport rep = f.Fuse(z);
  EXPECT_EQ(rep.outcome, FuseReport::Outcome::kAccepted);
  EXPECT_NEAR(f.pose().x, z.x, 1e-12);
  EXPECT_NEAR(f.pose().y, z.y, 1e-12);
  EXPECT_NEAR(f.pose().theta, z.theta, 1e-12);
  EXPECT_NEAR(f.covariance().norm(), 0.0, 1e-12);
}

TEST(PoseFilter, PredictIsDeadReckoningFromLastFusedPose) {
  PoseFilter f;
  f.Reset({1.0, 2.0, 0.5 * kPi});
  f.Predict({0.3, 0.0, 0.0}, 1.0);  // forward along +y in the world
  EXPECT_NEAR(f.pose().x, 1.0, 1e-12);
  EXPECT_NEAR(f.pose().y, 2.3, 1e-12);
  // P grows by Q = diag(q²)·T.
  const double p0 = DefaultPoseFilterDef().p0_xy, q = DefaultPoseFilterDef().q_xy;
  EXPECT_NEAR(f.covariance()(0, 0), p0 * p0 + q * q, 1e-15);
}

// The paper's filter (A = I, B = T·I, H = I, diagonal Q and R) against its closed form over
// several predict / fuse cycles with periods T ≠ 1 and R > 0: x⁻ = x + T·u (u the odometry twist
// in the world at the mid-step heading), P⁻ = P + Q·T, K = P⁻ (P⁻ + R)⁻¹, x = x⁻ + K (z − x⁻),
// P = (I − K) P⁻. Every matrix is diagonal, so the closed form is per component.
TEST(PoseFilter, PredictAndFuseMatchTheClosedFormWithPeriodNotOne) {
  PoseFilterDef def;
  def.q_xy = 0.02;
  def.q_theta = 0.03;
  def.r_xy = 0.015;
  def.r_theta = 0.02;
  def.p0_xy = 0.04;
  def.p0_theta = 0.05;
  def.gate = false;
  def.adaptive_r = false;
  PoseFilter f(def);
  f.Reset({1.0, 2.0, 0.3});
  double x[3] = {1.0, 2.0, 0.3};
  double P[3] = {def.p0_xy * def.p0_xy, def.p0_xy * def.p0_xy, def.p0_theta * def.p0_theta};
  const double q[3] = {def.q_xy * def.q_xy, def.q_xy * def.q_xy, def.q_theta * def.q_theta};
  const double R[3] = {def.r_xy * def.r_xy, def.r_xy * def.r_xy, def.r_theta * def.r_theta};
  const double periods[] = {1.0 / 15.0, 0.1, 0.025, 0.3};
  for (int k = 0; k < 4; ++k) {
    const double T = periods[k];
    const BodyTwist odo{0.3, 0.1 * (k - 1), 0.2 - 0.15 * k};
    ASSERT_TRUE(f.Predict(odo, T));
    const double th = x[2] + 0.5 * odo.omega * T;
    const double u[3] = {odo.vx * std::cos(th) - odo.vy * std::sin(th),
                         odo.vx * std::sin(th) + odo.vy * std::cos(th), odo.omega};
    for (int i = 0; i < 3; ++i) {
      x[i] += T * u[i];
      P[i] += q[i] * T;
    }
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f.covariance()(i, i), P[i], 1e-15) << k << " " << i;
    EXPECT_NEAR(f.pose().x, x[0], 1e-12) << k;
    EXPECT_NEAR(f.pose().y, x[1], 1e-12) << k;
    EXPECT_NEAR(f.pose().theta, x[2], 1e-12) << k;
    // A beacon sample a few centimetres off the prediction.
    const Pose2 z{x[0] + 0.03, x[1] - 0.02, x[2] + 0.01};
    const double zz[3] = {z.x, z.y, z.theta};
    ASSERT_EQ(f.Fuse(z).outcome, FuseReport::Outcome::kAccepted);
    for (int i = 0; i < 3; ++i) {
      const double K = P[i] / (P[i] + R[i]);
      x[i] += K * (zz[i] - x[i]);
      P[i] *= 1.0 - K;
    }
    EXPECT_NEAR(f.pose().x, x[0], 1e-12) << k;
    EXPECT_NEAR(f.pose().y, x[1], 1e-12) << k;
    EXPECT_NEAR(f.pose().theta, x[2], 1e-12) << k;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(f.covariance()(i, i), P[i], 1e-12 * P[i]) << k << " " << i;
      for (int j = 0; j < 3; ++j) {
        if (j != i) {
          EXPECT_EQ(f.covariance()(i, j), 0.0);
        }
      }
    }
  }
}

TEST(PoseFilter, GateRejectsOneMetreOutlierAndAcceptsNormalSamples) {
  PoseFilterDef def;
  def.gate = true;
  def.gate_probability = 0.999;
  def.r_xy = 0.02;
  def.r_theta = 0.02;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  testutil::TestNoise n(7);
  int rejected_normal = 0;
  for (int k = 0; k < 200; ++k) {
    f.Predict({0.0, 0.0, 0.0}, 0.1);
    const FuseReport rep = f.Fuse({0.02 * n.Normal(), 0.02 * n.Normal(), 0.02 * n.Normal()});
    if (rep.outcome != FuseReport::Outcome::kAccepted) ++rejected_normal;
    if (k == 100) {
      // Injected 1 m interference outlier.
      f.Predict({0.0, 0.0, 0.0}, 0.1);
      const Pose2 before = f.pose();
      const FuseReport out = f.Fuse({1.0, 0.0, 0.0});
      EXPECT_EQ(out.outcome, FuseReport::Outcome::kRejected);
      EXPECT_GT(out.nis, f.gate_threshold());
      EXPECT_DOUBLE_EQ(f.pose().x, before.x);  // state untouched
    }
  }
  EXPECT_LE(rejected_normal, 2);  // 0.1 % expected at p = 0.999
  // With the gate off the same outlier pulls the estimate.
  def.gate = false;
  f.SetDef(def);
  f.Fuse({1.0, 0.0, 0.0});
  EXPECT_GT(f.pose().x, 0.05);
}

TEST(PoseFilter, GateReinitialisesWhenLost) {
  PoseFilterDef def;
  def.gate_reset_after = 3;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  f.Predict({}, 0.1);
  // The beacon consistently says x = 2 (the filter is lost); one sample of the streak is itself
  // an outlier, which the median ignores.
  EXPECT_EQ(f.Fuse({2.0, 0, 0}).outcome, FuseReport::Outcome::kRejected);
  EXPECT_EQ(f.Fuse({7.0, 0, 0}).outcome, FuseReport::Outcome::kRejected);
  const FuseReport rep = f.Fuse({2.02, 0, 0});
  EXPECT_EQ(rep.outcome, FuseReport::Outcome::kReinitialised);
  EXPECT_FALSE(rep.message.empty());
  EXPECT_NEAR(f.pose().x, 2.02, 1e-12);
  EXPECT_EQ(f.Fuse({2.01, 0, 0}).outcome, FuseReport::Outcome::kAccepted);
}

TEST(PoseFilter, AngleInnovationWrapsAcrossPi) {
  PoseFilterDef def;
  def.gate = true;
  PoseFilter f(def);
  f.Reset({0, 0, kPi - 0.01});
  f.Predict({}, 0.1);
  // The beacon reads -π + 0.01: 0.02 rad away, not 2π - 0.02.
  const FuseReport rep = f.Fuse({0, 0, -kPi + 0.01});
  EXPECT_EQ(rep.outcome, FuseReport::Outcome::kAccepted);
  EXPECT_NEAR(rep.innovation(2), 0.02, 1e-12);
  EXPECT_GT(std::abs(f.pose().theta), kPi - 0.011);  // stays near ±π, not near 0
  // Predicting through +π wraps to the negative side.
  f.Reset({0, 0, kPi - 0.01});
  f.Predict({0, 0, 0.2}, 0.1);
  EXPECT_NEAR(f.pose().theta, -kPi + 0.01, 1e-12);
}

TEST(PoseFilter, AdaptiveRLearnsTheBeaconNoise) {
  PoseFilterDef def;
  def.gate = false;
  def.r_xy = 0.005;  // nominal far too optimistic
  def.r_theta = 0.005;
  def.adaptive_r = true;
  def.adaptive_window = 100;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  testutil::TestNoise n(3);
  for (int k = 0; k < 400; ++k) {
    f.Predict({}, 0.1);
    f.Fuse({0.05 * n.Normal(), 0.05 * n.Normal(), 0.03 * n.Normal()});
  }
  EXPECT_NEAR(std::sqrt(f.measurement_cov()(0, 0)), 0.05, 0.015);
  EXPECT_NEAR(std::sqrt(f.measurement_cov()(2, 2)), 0.03, 0.01);
}

TEST(PoseFilter, AdaptiveRWithGateRecoversFromOptimisticRAndIgnoresOutliers) {
  PoseFilterDef def;
  def.gate = true;
  def.r_xy = 0.003;  // the beacon is really 10x noisier
  def.r_theta = 0.003;
  def.adaptive_r = true;
  def.adaptive_window = 60;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  testutil::TestNoise n(5);
  int late_rejections = 0, late_good = 0;
  for (int k = 0; k < 600; ++k) {
    f.Predict({}, 0.1);
    Pose2 z{0.03 * n.Normal(), 0.03 * n.Normal(), 0.03 * n.Normal()};
    const bool outlier = n.Uniform() < 0.05;
    if (outlier) z.x += 0.8;  // interference
    const FuseReport rep = f.Fuse(z);
    if (k >= 300 && !outlier) {
      ++late_good;
      if (rep.outcome != FuseReport::Outcome::kAccepted) ++late_rejections;
    }
    if (k >= 300 && outlier) {
      EXPECT_NE(rep.outcome, FuseReport::Outcome::kAccepted);
    }
  }
  EXPECT_NEAR(std::sqrt(f.measurement_cov()(0, 0)), 0.03, 0.008);  // outliers did not inflate it
  EXPECT_LT(late_rejections, late_good / 50);
}

TEST(PoseFilter, SingularInnovationCovarianceIsReportedNotPropagated) {
  PoseFilterDef def;
  def.q_xy = def.q_theta = 0.0;
  def.r_xy = def.r_theta = 0.0;
  def.gate = false;
  PoseFilter f(def);
  f.Reset({0, 0, 0});
  EXPECT_EQ(f.Fuse({0.1, 0, 0}).outcome, FuseReport::Outcome::kAccepted);  // P -> 0
  f.Predict({}, 0.1);
  const FuseReport rep = f.Fuse({0.2, 0, 0});
  EXPECT_EQ(rep.outcome, FuseReport::Outcome::kFault);
  EXPECT_FALSE(rep.message.empty());
  EXPECT_TRUE(std::isfinite(f.pose().x));
  EXPECT_NEAR(f.pose().x, 0.1, 1e-12);
  EXPECT_FALSE(f.Predict({std::nan(""), 0, 0}, 0.1));
  EXPECT_TRUE(std::isfinite(f.pose().x));
}

}  // namespace
}  // namespace formsim::control::agv
