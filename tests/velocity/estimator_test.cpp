// The sliding-window estimator on seeded synthetic runs: it recovers known odometry and gyro
// biases, its speed is better than odometry, visual-inertial-only works without odometry, and
// marginalisation keeps the result of a much longer window.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/velocity/synthetic_run.hpp"

using velocity_test::RunSynthetic;
using velocity_test::SyntheticConfig;
using velocity_test::SyntheticSample;
namespace cv = formsim::control::velocity;

namespace {

// Mean of f over samples with t >= t_from.
template <class F>
double MeanAfter(const std::vector<SyntheticSample>& s, double t_from, F f) {
  double sum = 0.0;
  int n = 0;
  for (const auto& x : s)
    if (x.t >= t_from) {
      sum += f(x);
      ++n;
    }
  return n ? sum / n : NAN;
}

cv::SlidingWindowDef DefFor(const SyntheticConfig& c) {
  cv::SlidingWindowDef d;
  const double imu_dt = c.imu_every * c.fine_dt, odo_dt = c.odo_every * c.fine_dt;
  d.imu.gyro_noise_density = c.gyro_sigma * std::sqrt(imu_dt);
  d.imu.accel_noise_density = c.accel_sigma * std::sqrt(imu_dt);
  d.odometry.speed_noise_density = c.speed_sigma * std::sqrt(odo_dt);
  d.odometry.yaw_rate_noise_density = c.yaw_rate_sigma * std::sqrt(odo_dt);
  d.bearing_sigma = c.bearing_sigma;
  return d;
}

}  // namespace

TEST(SlidingWindowEstimator, RecoversKnownOdometryAndGyroBias) {
  SyntheticConfig c;
  c.duration = 25.0;
  double max_ms = 0.0;
  // The biases of this run are constant: the estimator is told they wander slowly.
  cv::SlidingWindowDef d = DefFor(c);
  d.odometry.speed_bias_rw = d.odometry.yaw_rate_bias_rw = 0.002;
  const auto run = RunSynthetic(c, d, &max_ms);
  for (const auto& s : run) ASSERT_TRUE(s.ok) << "fault at t=" << s.t;
  const double bv = MeanAfter(run, 15.0, [](const SyntheticSample& s) { return s.bv; });
  const double bw = MeanAfter(run, 15.0, [](const SyntheticSample& s) { return s.bw; });
  const double bg = MeanAfter(run, 15.0, [](const SyntheticSample& s) { return s.bg; });
  EXPECT_NEAR(bv, c.speed_bias, 0.006);
  EXPECT_NEAR(bw, c.yaw_rate_bias, 0.004);
  EXPECT_NEAR(bg, c.gyro_bias, 0.002);
  // The fused speed error is far below the odometry bias.
  const double rmse = std::sqrt(MeanAfter(run, 5.0, [](const SyntheticSample& s) {
    return (s.est_speed - s.true_speed) * (s.est_speed - s.true_speed);
  }));
  EXPECT_LT(rmse, 0.3 * c.speed_bias);
  std::printf(
      "bias: bv %.4f (true %.4f) bw %.4f (true %.4f) bg %.4f (true %.4f); speed RMSE %.4f; "
      "max update %.2f ms\n",
      bv, c.speed_bias, bw, c.yaw_rate_bias, bg, c.gyro_bias, rmse, max_ms);
}

TEST(SlidingWindowEstimator, VisualInertialOnlyTracksSpeedWithoutOdometry) {
  SyntheticConfig c;
  c.duration = 20.0;
  cv::SlidingWindowDef d = DefFor(c);
  d.use_odometry = false;
  d.use_nonholonomic = false;
  const auto run = RunSynthetic(c, d);
  for (const auto& s : run) ASSERT_TRUE(s.ok) << "fault at t=" << s.t;
  const double rmse = std::sqrt(MeanAfter(run, 3.0, [](const SyntheticSample& s) {
    return (s.est_speed - s.true_speed) * (s.est_speed - s.true_speed);
  }));
  EXPECT_LT(rmse, 0.05);
  EXPECT_GT(rmse, 0.0);
  std::printf("VI-only speed RMSE %.4f\n", rmse);
}

TEST(SlidingWindowEstimator, MarginalisationKeepsTheOptimum) {
  // Right after an update (solve + Schur-complement marginalisation), solving again must not
  // move the window: the prior carries exactly the gradient and curvature of what was removed.
  SyntheticConfig c;
  c.duration = 10.0;
  std::vector<double> change;
  const auto run = RunSynthetic(c, DefFor(c), nullptr, &change);
  ASSERT_GT(change.size(), 30u);
  std::sort(change.begin(), change.end());
  std::printf("re-optimisation change: median %.2e, max %.2e\n", change[change.size() / 2],
              change.back());
  EXPECT_LT(change[change.size() / 2], 1e-6);
  EXPECT_LT(change.back(), 1e-3);
}

TEST(SlidingWindowEstimator, ShortWindowAgreesWithLongWindow) {
  SyntheticConfig c;
  c.duration = 8.0;
  cv::SlidingWindowDef small = DefFor(c), big = DefFor(c);
  big.window_size = 40;  // no marginalisation within 8 s (32 keyframes)
  const auto a = RunSynthetic(c, small);
  const auto b = RunSynthetic(c, big);
  ASSERT_EQ(a.size(), b.size());
  double max_dv = 0.0, err_a = 0.0, err_b = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    max_dv = std::max(max_dv, std::abs(a[i].est_speed - b[i].est_speed));
    err_a += std::pow(a[i].est_speed - a[i].true_speed, 2) / a.size();
    err_b += std::pow(b[i].est_speed - b[i].true_speed, 2) / b.size();
  }
  std::printf("window 8 vs 40: max speed difference %.4f, RMSE %.4f vs %.4f\n", max_dv,
              std::sqrt(err_a), std::sqrt(err_b));
  // The filtered newest state of the short window stays close to the batch solution (their
  // landmark sets differ: long tracks are re-started in the short window).
  EXPECT_LT(max_dv, 0.02);
  EXPECT_LT(std::sqrt(err_a), 1.5 * std::sqrt(err_b) + 0.002);
}
