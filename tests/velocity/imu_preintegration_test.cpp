// IMU pre-integration against direct integration of a known planar motion, bias Jacobians
// against re-integration, and the propagated covariance against a Monte-Carlo estimate.
#include "control/velocity/imu_preintegration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/rng.hpp"

namespace cv = formsim::control::velocity;
using cv::Mat2d;
using cv::Vec2d;

namespace {

// A known smooth motion: heading, position, velocity and acceleration in closed form.
struct KnownMotion {
  double theta(double t) const { return 0.4 * t + 0.3 * std::sin(1.3 * t); }
  double omega(double t) const { return 0.4 + 0.39 * std::cos(1.3 * t); }
  Vec2d p(double t) const {
    return {0.5 * t + 0.8 * std::sin(0.7 * t), 0.6 * (1.0 - std::cos(0.9 * t))};
  }
  Vec2d v(double t) const { return {0.5 + 0.56 * std::cos(0.7 * t), 0.54 * std::sin(0.9 * t)}; }
  Vec2d a(double t) const { return {-0.392 * std::sin(0.7 * t), 0.486 * std::cos(0.9 * t)}; }
  // What an ideal IMU measures at t: yaw rate and specific force in the body frame.
  double gyro(double t) const { return omega(t); }
  Vec2d accel(double t) const { return cv::Rot(theta(t)).transpose() * a(t); }
};

}  // namespace

TEST(ImuPreintegration, MatchesClosedFormMotion) {
  const KnownMotion m;
  const double t0 = 0.7, T = 1.5, dt = 1e-3;
  cv::ImuPreintegration pre(0.0, Vec2d::Zero(), cv::ImuNoise{});
  const int n = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < n; ++k) {
    const double tm = t0 + (k + 0.5) * dt;  // mid-point sampling
    pre.Integrate(dt, m.gyro(tm), m.accel(tm));
  }
  const double t1 = t0 + T;
  const Mat2d RiT = cv::Rot(m.theta(t0)).transpose();
  EXPECT_NEAR(pre.sum_dt(), T, 1e-12);
  EXPECT_NEAR(pre.delta_theta(), m.theta(t1) - m.theta(t0), 1e-6);
  const Vec2d dv = RiT * (m.v(t1) - m.v(t0));
  const Vec2d dp = RiT * (m.p(t1) - m.p(t0) - m.v(t0) * T);
  EXPECT_NEAR((pre.delta_v() - dv).norm(), 0.0, 1e-5);
  EXPECT_NEAR((pre.delta_p() - dp).norm(), 0.0, 1e-5);
  // The numbers are not trivially small: the motion really turned and accelerated.
  EXPECT_GT(std::abs(pre.delta_theta()), 0.4);
  EXPECT_GT(dv.norm(), 0.3);
}

TEST(ImuPreintegration, EqualsDirectWorldFrameIntegration) {
  // Direct integration in the world frame with the same samples and the same mid-point rule,
  // starting from a known state, must give the pre-integrated result once mapped to frame i.
  const KnownMotion m;
  const double dt = 0.005, bg = 0.02;
  const Vec2d ba(0.05, -0.03);
  formsim::sim::Rng rng(3);
  auto noise = [&rng]() { return 0.05 * rng.Normal(); };
  cv::ImuPreintegration pre(bg, ba, cv::ImuNoise{});
  double th = 0.3;
  Vec2d p(1.0, -2.0), v(0.4, 0.1);
  const double th0 = th;
  const Vec2d p0 = p, v0 = v;
  for (int k = 0; k < 300; ++k) {
    const double gyro = m.gyro(k * dt) + bg + noise();
    const Vec2d acc = m.accel(k * dt) + ba + Vec2d(noise(), noise());
    pre.Integrate(dt, gyro, acc);
    const double w = gyro - bg;
    const Vec2d a = cv::Rot(th + 0.5 * w * dt) * (acc - ba);
    p += v * dt + 0.5 * a * dt * dt;
    v += a * dt;
    th += w * dt;
  }
  const Mat2d RiT = cv::Rot(th0).transpose();
  const double T = pre.sum_dt();
  EXPECT_NEAR(pre.delta_theta(), th - th0, 1e-12);
  EXPECT_LT((pre.delta_v() - RiT * (v - v0)).norm(), 1e-12);
  EXPECT_LT((pre.delta_p() - RiT * (p - p0 - v0 * T)).norm(), 1e-12);
}

TEST(ImuPreintegration, BiasJacobiansMatchReintegration) {
  const KnownMotion m;
  const double dt = 0.005;
  cv::ImuPreintegration pre(0.01, Vec2d(0.02, 0.01), cv::ImuNoise{});
  for (int k = 0; k < 200; ++k) pre.Integrate(dt, m.gyro(k * dt) + 0.01, m.accel(k * dt));
  const double h = 1e-6;
  // Gyro bias.
  cv::ImuPreintegration plus = pre;
  plus.Repropagate(pre.lin_bg() + h, pre.lin_ba());
  EXPECT_NEAR((plus.delta_theta() - pre.delta_theta()) / h, pre.dtheta_dbg(), 1e-6);
  EXPECT_LT(((plus.delta_v() - pre.delta_v()) / h - pre.dv_dbg()).norm(), 1e-4);
  EXPECT_LT(((plus.delta_p() - pre.delta_p()) / h - pre.dp_dbg()).norm(), 1e-4);
  // Accelerometer bias, each axis.
  for (int axis = 0; axis < 2; ++axis) {
    Vec2d ba = pre.lin_ba();
    ba(axis) += h;
    plus = pre;
    plus.Repropagate(pre.lin_bg(), ba);
    EXPECT_LT(((plus.delta_v() - pre.delta_v()) / h - pre.dv_dba().col(axis)).norm(), 1e-5);
    EXPECT_LT(((plus.delta_p() - pre.delta_p()) / h - pre.dp_dba().col(axis)).norm(), 1e-5);
  }
  // First-order correction is close to re-integration for a finite bias change.
  plus = pre;
  plus.Repropagate(pre.lin_bg() + 0.01, pre.lin_ba() + Vec2d(0.03, -0.02));
  EXPECT_LT(
      (pre.CorrectedV(pre.lin_bg() + 0.01, pre.lin_ba() + Vec2d(0.03, -0.02)) - plus.delta_v())
          .norm(),
      1e-3);
}

TEST(ImuPreintegration, CovarianceMatchesMonteCarlo) {
  const KnownMotion m;
  cv::ImuNoise noise;
  noise.gyro_noise_density = 0.01;
  noise.accel_noise_density = 0.05;
  const double dt = 0.01;
  const int n = 50, runs = 3000;
  cv::ImuPreintegration ref(0.0, Vec2d::Zero(), noise);
  for (int k = 0; k < n; ++k) ref.Integrate(dt, m.gyro(k * dt), m.accel(k * dt));
  formsim::sim::Rng rng(11);
  const double sg = noise.gyro_noise_density / std::sqrt(dt);
  const double sa = noise.accel_noise_density / std::sqrt(dt);
  auto g = [&]() { return sg * rng.Normal(); };
  auto a = [&]() { return sa * rng.Normal(); };
  Eigen::Matrix<double, 5, 5> cov = Eigen::Matrix<double, 5, 5>::Zero();
  for (int r = 0; r < runs; ++r) {
    cv::ImuPreintegration pre(0.0, Vec2d::Zero(), noise);
    for (int k = 0; k < n; ++k)
      pre.Integrate(dt, m.gyro(k * dt) + g(), m.accel(k * dt) + Vec2d(a(), a()));
    Eigen::Matrix<double, 5, 1> e;
    e << pre.delta_theta() - ref.delta_theta(), pre.delta_v() - ref.delta_v(),
        pre.delta_p() - ref.delta_p();
    cov += e * e.transpose() / runs;
  }
  // Diagonal within 10 % (3000 samples: about 2.6 % standard error) of the propagated one.
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(cov(i, i) / ref.covariance()(i, i), 1.0, 0.1) << "component " << i;
  // The θ-p correlation sign and size agree.
  EXPECT_NEAR(cov(0, 4) / std::sqrt(cov(0, 0) * cov(4, 4)),
              ref.covariance()(0, 4) / std::sqrt(ref.covariance()(0, 0) * ref.covariance()(4, 4)),
              0.1);
}
