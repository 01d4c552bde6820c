#pragma once
/// \file Residuals of the sliding-window estimator with their exact Jacobians, already whitened
/// (multiplied by the square root of the information matrix), so that the cost of each factor
/// is ½‖r‖². Every angle residual is wrapped to (-π, π]. Jacobian columns follow
/// KeyframeState::Index; feature Jacobians are w.r.t. the landmark's world position.

#include <Eigen/Dense>

#include "control/velocity/imu_preintegration.hpp"
#include "control/velocity/keyframe_state.hpp"
#include "control/velocity/odometry_preintegration.hpp"

namespace formsim::control::velocity {

/// IMU pre-integration factor between keyframes i and j (8 rows):
///   r_θ = θj - θi - Δθ(bgi)
///   r_v = Riᵀ (vj - vi) - Δv(bgi, bai)
///   r_p = Riᵀ (pj - pi - vi Δt) - Δp(bgi, bai)
///   r_bg = bgj - bgi,  r_ba = baj - bai   (bias random walk over Δt)
struct ImuFactor {
  static constexpr int kRows = 8;
  Eigen::Matrix<double, kRows, 1> r;
  Eigen::Matrix<double, kRows, KeyframeState::kDim> Ji, Jj;
};
ImuFactor EvaluateImuFactor(const ImuPreintegration& pre, const KeyframeState& i,
                            const KeyframeState& j);

/// Wheel-odometry factor between keyframes i and j (5 rows):
///   r_θ = θj - θi - Δθᴼ(bψi),  r_p = Riᵀ (pj - pi) - Δpᴼ(bvi, bψi),
///   r_bv = bvj - bvi,  r_bψ = bψj - bψi   (odometry bias random walk over Δt).
struct OdometryFactor {
  static constexpr int kRows = 5;
  Eigen::Matrix<double, kRows, 1> r;
  Eigen::Matrix<double, kRows, KeyframeState::kDim> Ji, Jj;
};
OdometryFactor EvaluateOdometryFactor(const OdometryPreintegration& pre, const KeyframeState& i,
                                      const KeyframeState& j);

/// Non-holonomic constraint of a wheeled robot at one keyframe: the lateral body-frame
/// velocity is zero up to `sigma` (m/s), which allows some sideways skid.
struct NonholonomicFactor {
  double r = 0.0;
  Eigen::Matrix<double, 1, KeyframeState::kDim> J;
};
NonholonomicFactor EvaluateNonholonomicFactor(const KeyframeState& k, double sigma);

/// Bearing of a point landmark seen by a camera looking along the body x axis, mounted
/// `camera_offset` metres ahead of the body origin: r = (atan2(q_y, q_x) - z) / σ with
/// q = R(θ)ᵀ (f - p) - [offset, 0]ᵀ.
struct BearingFactor {
  double r = 0.0;
  Eigen::Matrix<double, 1, KeyframeState::kDim> Jk;
  Eigen::Matrix<double, 1, 2> Jf;
  double depth = 0.0;  ///< q_x: positive when the landmark is in front of the camera
};
BearingFactor EvaluateBearingFactor(const KeyframeState& k, const Vec2d& landmark, double bearing,
                                    double sigma, double camera_offset);

/// Square root U of an information matrix, UᵀU = cov⁻¹, from the covariance (Cholesky with a
/// tiny jitter so that a zero-length interval stays finite).
Eigen::MatrixXd SqrtInformation(const Eigen::MatrixXd& cov);

}  // namespace formsim::control::velocity
