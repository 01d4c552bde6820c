#pragma once
/// \file Planar IMU pre-integration between two keyframes (Forster et al. 2017, reduced to the
/// plane as in the paper's ref. [8] and VINS-Mono): yaw-rate gyro and 2-axis accelerometer in
/// the body frame, the floor is level so gravity has no in-plane component.
///
/// With b̄g, b̄a the bias linearisation point, per sample (dt, ω̃, ã):
///   w = ω̃ - b̄g,  a = ã - b̄a,  R = R(Δθ + w dt / 2)   (mid-point rotation)
///   Δp += Δv dt + R a dt² / 2,   Δv += R a dt,   Δθ += w dt.
/// Δθ, Δv, Δp are expressed in the first keyframe's body frame. First-order bias Jacobians let
/// the optimiser correct them for a new bias without re-integrating; when the bias moves far,
/// Repropagate() integrates the stored samples again. The covariance of [δθ, δv, δp] is
/// propagated from the white-noise densities.

#include <Eigen/Dense>
#include <vector>

#include "control/velocity/planar.hpp"

namespace formsim::control::velocity {

/// Continuous-time IMU noise model (densities), as in a data sheet.
struct ImuNoise {
  double gyro_noise_density = 1e-3;   ///< rad/s/√Hz
  double accel_noise_density = 1e-2;  ///< m/s²/√Hz
  double gyro_bias_rw = 1e-4;         ///< gyro bias random walk, rad/s²/√Hz
  double accel_bias_rw = 1e-3;        ///< accelerometer bias random walk, m/s³/√Hz
};

class ImuPreintegration {
 public:
  using Cov = Eigen::Matrix<double, 5, 5>;  ///< order: θ, v (2), p (2)
  /// One raw IMU sample covering `dt` seconds.
  struct Sample {
    double dt = 0.0;
    double gyro = 0.0;
    Vec2d accel = Vec2d::Zero();
  };

  ImuPreintegration(double bg_lin, const Vec2d& ba_lin, const ImuNoise& noise);

  /// Adds one sample (gyro yaw rate in rad/s, accelerometer in m/s², body frame).
  void Integrate(double dt, double gyro, const Vec2d& accel);
  /// Integrates all stored samples again about a new bias linearisation point.
  void Repropagate(double bg_lin, const Vec2d& ba_lin);

  double sum_dt() const { return sum_dt_; }
  double delta_theta() const { return dtheta_; }
  const Vec2d& delta_v() const { return dv_; }
  const Vec2d& delta_p() const { return dp_; }
  const Cov& covariance() const { return cov_; }
  double lin_bg() const { return bg_lin_; }
  const Vec2d& lin_ba() const { return ba_lin_; }
  const std::vector<Sample>& samples() const { return samples_; }
  const ImuNoise& noise() const { return noise_; }

  /// Bias Jacobians of the pre-integrated quantities.
  double dtheta_dbg() const { return dtheta_dbg_; }
  const Vec2d& dv_dbg() const { return dv_dbg_; }
  const Mat2d& dv_dba() const { return dv_dba_; }
  const Vec2d& dp_dbg() const { return dp_dbg_; }
  const Mat2d& dp_dba() const { return dp_dba_; }

  /// Pre-integrated values corrected to first order for biases (bg, ba).
  double CorrectedTheta(double bg) const;
  Vec2d CorrectedV(double bg, const Vec2d& ba) const;
  Vec2d CorrectedP(double bg, const Vec2d& ba) const;

 private:
  void Reset();
  void Step(const Sample& s);

  ImuNoise noise_;
  double bg_lin_ = 0.0;
  Vec2d ba_lin_ = Vec2d::Zero();
  std::vector<Sample> samples_;

  double sum_dt_ = 0.0, dtheta_ = 0.0;
  Vec2d dv_ = Vec2d::Zero(), dp_ = Vec2d::Zero();
  Cov cov_ = Cov::Zero();
  double dtheta_dbg_ = 0.0;
  Vec2d dv_dbg_ = Vec2d::Zero(), dp_dbg_ = Vec2d::Zero();
  Mat2d dv_dba_ = Mat2d::Zero(), dp_dba_ = Mat2d::Zero();
};

}  // namespace formsim::control::velocity
