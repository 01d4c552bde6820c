#pragma once
// A synthetic planar run for estimator tests, independent of the simulator: a unicycle follows
// smooth speed profiles; an IMU, wheel odometry with additive biases and a bearing camera
// observe it with seeded noise; the estimator is fed in time order.
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "control/common/angle.hpp"
#include "control/velocity/sliding_window_estimator.hpp"
#include "sim/core/rng.hpp"

namespace velocity_test {

namespace cv = formsim::control::velocity;

struct SyntheticConfig {
  double duration = 30.0;
  double fine_dt = 0.001;  // ground-truth integration step
  int imu_every = 5;       // 200 Hz
  int odo_every = 20;      // 50 Hz
  int kf_every = 250;      // 4 Hz
  double gyro_bias = 0.02;
  cv::Vec2d accel_bias{0.05, -0.03};
  double speed_bias = 0.03;                           // odometry b_v, m/s
  double yaw_rate_bias = 0.01;                        // odometry b_ψ, rad/s
  double gyro_sigma = 0.002, accel_sigma = 0.02;      // per-sample white noise at 200 Hz
  double speed_sigma = 0.005, yaw_rate_sigma = 0.01;  // per-sample at 50 Hz
  double bearing_sigma = 0.002;
  double fov = 1.6, range = 8.0;
  int landmarks = 400;
  double area = 14.0;  // landmarks uniform in [-area, area]²
  unsigned seed = 5;
  std::function<double(double)> speed = [](double t) {
    return std::min(t / 2.0, 1.0) * (0.4 + 0.15 * std::sin(0.5 * t));
  };
  std::function<double(double)> yaw_rate = [](double t) {
    return 0.25 * std::sin(0.21 * t) + 0.05;
  };
};

struct SyntheticSample {
  double t = 0.0;
  double true_speed = 0.0, est_speed = 0.0, odo_speed = 0.0;
  double bv = 0.0, bw = 0.0, bg = 0.0;
  cv::Vec2d true_p, est_p;
  bool ok = true;
};

// Runs the estimator configured by `def` over the synthetic data; one sample per keyframe.
// `reopt_change`, when given, receives the largest state change a re-optimisation right after
// each update makes (zero when the update converged and marginalisation kept the optimum);
// `after_update`, when given, sees the estimator after every update.
inline std::vector<SyntheticSample> RunSynthetic(
    const SyntheticConfig& c, cv::SlidingWindowDef def, double* max_update_ms = nullptr,
    std::vector<double>* reopt_change = nullptr,
    const std::function<void(const cv::SlidingWindowEstimator&)>& after_update = nullptr) {
  // The project's portable generator: the same numbers with every standard library.
  formsim::sim::Rng rng(c.seed);
  auto n01 = [&rng]() { return rng.Normal(); };
  std::vector<cv::Vec2d> lm(c.landmarks);
  for (auto& l : lm) {
    const double x = rng.Uniform(-c.area, c.area);
    l = cv::Vec2d(x, rng.Uniform(-c.area, c.area));
  }

  auto observe = [&](const cv::Vec2d& p, double th) {
    std::vector<cv::BearingObservation> obs;
    for (int i = 0; i < c.landmarks; ++i) {
      const cv::Vec2d q = cv::Rot(th).transpose() * (lm[i] - p);
      const double b = std::atan2(q.y(), q.x());
      if (q.norm() < c.range && q.norm() > 0.3 && std::abs(b) < 0.5 * c.fov)
        obs.push_back({i, b + c.bearing_sigma * n01()});
    }
    return obs;
  };

  cv::SlidingWindowEstimator est(def);
  cv::Vec2d p(0.0, 0.0);
  double th = 0.0;
  cv::KeyframeState first;
  est.Initialize(first, observe(p, th));

  std::vector<SyntheticSample> out;
  const int steps = static_cast<int>(std::lround(c.duration / c.fine_dt));
  cv::Vec2d p_imu = p, v_imu = cv::Vec2d::Zero();
  double th_imu = th;
  double odo_dist = 0.0, odo_dth = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double t = k * c.fine_dt, tm = t - 0.5 * c.fine_dt;
    const double v = c.speed(tm), w = c.yaw_rate(tm);
    const double th_mid = th + 0.5 * w * c.fine_dt;
    p += v * c.fine_dt * cv::Vec2d(std::cos(th_mid), std::sin(th_mid));
    th += w * c.fine_dt;
    odo_dist += v * c.fine_dt;
    odo_dth += w * c.fine_dt;
    if (k % c.imu_every == 0) {
      // Interval-mean IMU sample (exact integrals of the motion over the interval).
      const double dt = c.imu_every * c.fine_dt;
      const cv::Vec2d v_now = c.speed(t) * cv::Vec2d(std::cos(th), std::sin(th));
      const double gyro = formsim::control::WrapToPi(th - th_imu) / dt;
      const cv::Vec2d acc = cv::Rot(th_imu + 0.5 * gyro * dt).transpose() * (v_now - v_imu) / dt;
      est.AddImu(dt, gyro + c.gyro_bias + c.gyro_sigma * n01(),
                 acc + c.accel_bias + c.accel_sigma * cv::Vec2d(n01(), n01()));
      v_imu = v_now;
      th_imu = th;
      p_imu = p;
    }
    if (k % c.odo_every == 0) {
      const double dt = c.odo_every * c.fine_dt;
      est.AddOdometry(dt, odo_dist / dt + c.speed_bias + c.speed_sigma * n01(),
                      odo_dth / dt + c.yaw_rate_bias + c.yaw_rate_sigma * n01());
      odo_dist = odo_dth = 0.0;
    }
    if (k % c.kf_every == 0) {
      const auto t0 = std::chrono::steady_clock::now();
      const cv::UpdateReport r = est.AddKeyframe(t, observe(p, th));
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (max_update_ms) *max_update_ms = std::max(*max_update_ms, ms);
      if (after_update) after_update(est);
      if (reopt_change) {
        cv::SlidingWindowEstimator copy = est;
        copy.Reoptimize();
        double change = 0.0;
        for (std::size_t f = 0; f < est.window().size(); ++f)
          change = std::max(change, (copy.window()[f].x - est.window()[f].x).cwiseAbs().maxCoeff());
        reopt_change->push_back(change);
      }
      SyntheticSample s;
      s.t = t;
      s.true_speed = c.speed(t);
      s.est_speed = est.latest().body_velocity().x();
      s.odo_speed = c.speed(t) + c.speed_bias;
      s.bv = est.latest().bv();
      s.bw = est.latest().bw();
      s.bg = est.latest().bg();
      s.true_p = p;
      s.est_p = est.latest().p();
      s.ok = r.ok;
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace velocity_test
