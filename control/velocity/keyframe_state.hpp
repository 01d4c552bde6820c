#pragma once
/// \file The state of one keyframe in the sliding window: planar pose, world-frame velocity,
/// IMU biases (gyro yaw-rate bias, accelerometer bias in the body frame) and the wheel
/// odometry biases of the paper's odometry model (ṽ = v + b_v + n_v, ψ̃ = ψ + b_ψ + n_ψ).
/// Stored as one Eigen vector (the optimiser's block) with named accessors.

#include <Eigen/Dense>

#include "control/velocity/planar.hpp"

namespace formsim::control::velocity {

struct KeyframeState {
  static constexpr int kDim = 10;
  /// Offsets of each quantity inside the 10-vector (also used for Jacobian columns).
  enum Index : int { kP = 0, kTheta = 2, kV = 3, kBg = 5, kBa = 6, kBv = 8, kBw = 9 };
  using Vector = Eigen::Matrix<double, kDim, 1>;

  Vector x = Vector::Zero();
  double t = 0.0;  ///< time stamp, s
  long id = 0;     ///< unique keyframe number (increasing)

  Vec2d p() const { return x.segment<2>(kP); }
  double theta() const { return x(kTheta); }
  Vec2d v() const { return x.segment<2>(kV); }
  double bg() const { return x(kBg); }
  Vec2d ba() const { return x.segment<2>(kBa); }
  double bv() const { return x(kBv); }
  double bw() const { return x(kBw); }

  void set_p(const Vec2d& p) { x.segment<2>(kP) = p; }
  void set_theta(double th) { x(kTheta) = th; }
  void set_v(const Vec2d& v) { x.segment<2>(kV) = v; }
  void set_bg(double b) { x(kBg) = b; }
  void set_ba(const Vec2d& b) { x.segment<2>(kBa) = b; }
  void set_bv(double b) { x(kBv) = b; }
  void set_bw(double b) { x(kBw) = b; }

  /// Velocity in the body frame: forward (x) and lateral (y) components.
  Vec2d body_velocity() const { return Rot(theta()).transpose() * v(); }
};

}  // namespace formsim::control::velocity
