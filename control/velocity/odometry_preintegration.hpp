#pragma once
/// \file Wheel-odometry pre-integration between two keyframes, with the paper's odometry model
/// ṽ = v + b_v + n_v and ψ̃ = ψ + b_ψ + n_ψ (section 1.3): forward speed and yaw rate measured
/// with additive biases (slip, radius error) and white noise. With b̄v, b̄ψ the linearisation
/// point, per sample (dt, ṽ, ψ̃):
///   u = ṽ - b̄v,  w = ψ̃ - b̄ψ,  Δp += R(Δθ + w dt / 2) [u dt, 0]ᵀ,  Δθ += w dt,
/// Δp in the first keyframe's body frame. First-order Jacobians in (b_v, b_ψ) and the covariance
/// of [δθ, δp] from the noise densities, as for the IMU.

#include <Eigen/Dense>
#include <vector>

#include "control/velocity/planar.hpp"

namespace formsim::control::velocity {

/// Odometry noise model: white-noise densities on the measured speeds and bias random walks.
struct OdometryNoise {
  double speed_noise_density = 0.01;     ///< n_v, m/s/√Hz
  double yaw_rate_noise_density = 0.02;  ///< n_ψ, rad/s/√Hz
  double speed_bias_rw = 0.01;           ///< b_v random walk, m/s²/√Hz
  double yaw_rate_bias_rw = 0.01;        ///< b_ψ random walk, rad/s²/√Hz
};

class OdometryPreintegration {
 public:
  using Cov = Eigen::Matrix3d;  ///< order: θ, p (2)
  struct Sample {
    double dt = 0.0;
    double speed = 0.0;
    double yaw_rate = 0.0;
  };

  OdometryPreintegration(double bv_lin, double bw_lin, const OdometryNoise& noise);

  /// Adds one odometry reading (forward speed m/s, yaw rate rad/s) valid over `dt` seconds.
  void Integrate(double dt, double speed, double yaw_rate);
  void Repropagate(double bv_lin, double bw_lin);

  double sum_dt() const { return sum_dt_; }
  double delta_theta() const { return dtheta_; }
  const Vec2d& delta_p() const { return dp_; }
  const Cov& covariance() const { return cov_; }
  double lin_bv() const { return bv_lin_; }
  double lin_bw() const { return bw_lin_; }
  const std::vector<Sample>& samples() const { return samples_; }
  const OdometryNoise& noise() const { return noise_; }
  double dtheta_dbw() const { return dtheta_dbw_; }
  const Vec2d& dp_dbv() const { return dp_dbv_; }
  const Vec2d& dp_dbw() const { return dp_dbw_; }

  double CorrectedTheta(double bw) const;
  Vec2d CorrectedP(double bv, double bw) const;

 private:
  void Reset();
  void Step(const Sample& s);

  OdometryNoise noise_;
  double bv_lin_ = 0.0, bw_lin_ = 0.0;
  std::vector<Sample> samples_;
  double sum_dt_ = 0.0, dtheta_ = 0.0;
  Vec2d dp_ = Vec2d::Zero();
  Cov cov_ = Cov::Zero();
  double dtheta_dbw_ = 0.0;
  Vec2d dp_dbv_ = Vec2d::Zero(), dp_dbw_ = Vec2d::Zero();
};

}  // namespace formsim::control::velocity
